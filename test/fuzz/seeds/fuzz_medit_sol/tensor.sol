MeshVersionFormatted 2

Dimension 3

SolAtVertices
4
1 3

1 0 1 0 0 1
4 0.5 2 0 0 1
100 0 1e-2 0 0 1
1 0.9 1 0.9 0.9 1

End
