// A 0.3 x 0.1 x 0.1 m block, the tetrahedral fixture of mesh_io_test.cc. Made with Gmsh 4.8.4:
//   gmsh -3 -format msh41 block.geo -o block_v41.msh
//   gmsh -3 -format msh22 block.geo -o block_v22.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.3, 0.1, 0.1};
Mesh.CharacteristicLengthMax = 0.05;
