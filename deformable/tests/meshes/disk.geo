// A disk of radius 0.1 m in the plane z = 0, the triangle fixture of mesh_io_test.cc. Made
// with Gmsh 4.8.4:
//   gmsh -2 -format msh41 disk.geo -o disk_v41.msh
SetFactory("OpenCASCADE");
Disk(1) = {0, 0, 0, 0.1};
Mesh.CharacteristicLengthMax = 0.04;
