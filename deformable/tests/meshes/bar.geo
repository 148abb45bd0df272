// A 3.0 x 0.1 x 0.1 m bar, the unstructured fixture of continuum_material_test.cc at two
// resolutions. Made with Gmsh 4.8.4:
//   gmsh -3 -format msh41 -setnumber h 0.05 bar.geo -o bar_h050.msh
//   gmsh -3 -format msh41 -setnumber h 0.033 bar.geo -o bar_h033.msh
SetFactory("OpenCASCADE");
DefineConstant[h = 0.05];
Box(1) = {0, 0, 0, 3.0, 0.1, 0.1};
Mesh.CharacteristicLengthMax = h;
