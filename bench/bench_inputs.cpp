// Writes the input files that examples refer to and the repository does not hold, so that the
// benchmark can time those examples too: box_hole.step (examples/brep_box_hole.json), the box
// [-1,1]x[-1,1]x[0,1] without the cylinder of radius 0.5 about the z axis, as the tests build it.
// Usage: bench_inputs DIR   (exit 0 when every file was written, 1 otherwise)
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <STEPControl_Writer.hxx>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: bench_inputs DIR\n";
    return 2;
  }
  const std::string path = std::string(argv[1]) + "/box_hole.step";
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-1, -1, 0), gp_Pnt(1, 1, 1)).Shape();
  const TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 0.5, 3).Shape();
  BRepAlgoAPI_Cut cut(box, hole);
  if (!cut.IsDone()) {
    std::cerr << "bench_inputs: the cut of the box failed\n";
    return 1;
  }
  STEPControl_Writer w;
  if (w.Transfer(cut.Shape(), STEPControl_AsIs) != IFSelect_RetDone || w.Write(path.c_str()) != IFSelect_RetDone) {
    std::cerr << "bench_inputs: cannot write " << path << "\n";
    return 1;
  }
  return 0;
}
