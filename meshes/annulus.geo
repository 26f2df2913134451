// The Varney & Green sealing dam (ri = 0.0355 m, ro = 0.0408 m) as a gmsh mesh for
// `set Mesh file = meshes/annulus.msh`. sealfe classifies the boundary by radius; the physical
// tags below only document which circle is which. Regenerate with
//   gmsh -2 -format msh2 -o meshes/annulus.msh meshes/annulus.geo
ri = 0.0355;
ro = 0.0408;
lc = 0.003;
Point(1) = {0, 0, 0, lc};
Point(2) = {ri, 0, 0, lc};
Point(3) = {0, ri, 0, lc};
Point(4) = {-ri, 0, 0, lc};
Point(5) = {0, -ri, 0, lc};
Point(6) = {ro, 0, 0, lc};
Point(7) = {0, ro, 0, lc};
Point(8) = {-ro, 0, 0, lc};
Point(9) = {0, -ro, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 8};
Circle(7) = {8, 1, 9};
Circle(8) = {9, 1, 6};
Curve Loop(1) = {5, 6, 7, 8};
Curve Loop(2) = {1, 2, 3, 4};
Plane Surface(1) = {1, 2};
Physical Curve("inner", 1) = {1, 2, 3, 4};
Physical Curve("outer", 2) = {5, 6, 7, 8};
Physical Surface("dam", 3) = {1};
Mesh.SubdivisionAlgorithm = 1; // all-quad mesh
