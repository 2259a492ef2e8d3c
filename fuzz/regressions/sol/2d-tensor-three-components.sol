# anisÿropic
MeshVersionFormatted 1
Diotropic
Me:hVnFo
Dimension
2
SolAtVertices
2
1 3
0 0 1 0 0 1
nd
