#pragma once
// The solid of examples/brep_box_hole.json's STEP file, which the repository does not hold: the box
// [-1,1]x[-1,1]x[0,1] without the cylinder of radius 0.5 about the z axis (volume 4 - pi / 4). The
// tests (tests/bridge_brep.cpp) and the benchmark's input writer (bench/bench_inputs.cpp) both
// build it here.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <STEPControl_Writer.hxx>
#include <string>

namespace sweep_test {

/// Writes the box with its hole to `path` as STEP; false when the cut or the writing fails.
inline bool write_box_with_hole(const std::string& path) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-1, -1, 0), gp_Pnt(1, 1, 1)).Shape();
  const TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 0.5, 3).Shape();
  BRepAlgoAPI_Cut cut(box, hole);
  if (!cut.IsDone()) return false;
  STEPControl_Writer w;
  return w.Transfer(cut.Shape(), STEPControl_AsIs) == IFSelect_RetDone && w.Write(path.c_str()) == IFSelect_RetDone;
}

}  // namespace sweep_test
