# anisotropic
MeshVersionFormatted 1
Dimension
3
SolAtVertices
2
1 3
1 0 1 0 0 1
100 0.5 4 0 0 1e4
End
