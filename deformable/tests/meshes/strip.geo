// A 3.0 x 0.1 m strip in the plane z = 0, the unstructured triangle fixture of
// continuum_material_test.cc at two resolutions. Made with Gmsh 4.8.4:
//   gmsh -2 -format msh41 -setnumber h 0.025 strip.geo -o strip_h025.msh
//   gmsh -2 -format msh41 -setnumber h 0.0125 strip.geo -o strip_h0125.msh
SetFactory("OpenCASCADE");
DefineConstant[h = 0.025];
Rectangle(1) = {0, 0, 0, 3.0, 0.1};
Mesh.CharacteristicLengthMax = h;
