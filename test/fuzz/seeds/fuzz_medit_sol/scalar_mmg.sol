MeshVersionFormatted
2
# sizes, as MMG writes them
Dimension
3

SolAtVertices
3
1
1
0.1
0.25
1e-3

End
