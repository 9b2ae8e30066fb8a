// Shape output by extension and reading back, with no half-written file left behind.
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StlAPI_Writer.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cctype>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "base/internal.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {

std::string file_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return e;
}

namespace {

void write_off(const TopoDS_Shape& s, const std::string& path) {
  std::map<std::array<double, 3>, int> index;
  std::vector<std::array<double, 3>> verts;
  std::vector<std::array<int, 3>> tris;
  for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) {
    TopoDS_Face f = TopoDS::Face(ex.Current());
    TopLoc_Location loc;
    Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(f, loc);
    if (t.IsNull()) throw ComputeError("face without triangulation while writing OFF");
    std::vector<int> map(t->NbNodes() + 1);
    for (int i = 1; i <= t->NbNodes(); ++i) {
      gp_Pnt p = t->Node(i).Transformed(loc.Transformation());
      std::array<double, 3> k{p.X(), p.Y(), p.Z()};
      auto it = index.find(k);
      if (it == index.end()) {
        it = index.emplace(k, int(verts.size())).first;
        verts.push_back(k);
      }
      map[i] = it->second;
    }
    const bool rev = f.Orientation() == TopAbs_REVERSED;
    for (int i = 1; i <= t->NbTriangles(); ++i) {
      int a, b, c;
      t->Triangle(i).Get(a, b, c);
      if (rev) std::swap(b, c);
      if (map[a] == map[b] || map[b] == map[c] || map[a] == map[c]) continue;
      tris.push_back({map[a], map[b], map[c]});
    }
  }
  std::ofstream o(path);
  o.precision(17);
  o << "OFF\n" << verts.size() << " " << tris.size() << " 0\n";
  for (auto& v : verts) o << v[0] << " " << v[1] << " " << v[2] << "\n";
  for (auto& t : tris) o << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  if (!o) throw ComputeError("cannot write '" + path + "'");
}

}  // namespace

void quiet_occt() {
  static bool done = false;
  if (done) return;
  done = true;
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
}

bool supported_output(const std::string& path) {
  std::string e = file_extension(path);
  return e == "step" || e == "stp" || e == "brep" || e == "stl" || e == "off";
}

void write_shape(const Shape& shape, const std::string& path, double mesh_tolerance) {
  const std::string e = file_extension(path);
  if (!supported_output(path))
    throw InputError("-o", "unsupported output extension '." + e + "' (expected .step, .stp, .brep, .stl or .off)");
  const std::string tmp = path + ".partial";
  quiet_occt();
  try {
    const TopoDS_Shape& s = shape.shape;
    bool ok = true;
    if (e == "step" || e == "stp") {
      // A STEP round trip can change a solid (the reader rebuilds trimming, and faces on spheres
      // through their poles can come back as their complement): the file is read back and its
      // volume compared with the solid's before it is kept.
      STEPControl_Writer w;
      Interface_Static::SetCVal("write.step.schema", "AP214IS");
      ok = w.Transfer(s, STEPControl_AsIs) == IFSelect_RetDone && w.Write(tmp.c_str()) == IFSelect_RetDone;
      if (ok) {
        GProp_GProps a;
        BRepGProp::VolumeProperties(s, a, 1e-10);
        if (std::abs(a.Mass()) > 0) {
          const double back = file_volume(tmp);
          if (std::abs(back - a.Mass()) > 1e-6 * std::abs(a.Mass()))
            throw ComputeError("the STEP file does not read back to the solid's volume (" + std::to_string(back) +
                               " vs " + std::to_string(a.Mass()) + "); write .brep instead");
        }
      }
    } else if (e == "brep") {
      ok = BRepTools::Write(s, tmp.c_str());
    } else {
      BRepMesh_IncrementalMesh mesh(s, mesh_tolerance, false, 0.1, false);
      if (e == "stl") {
        StlAPI_Writer w;
        w.ASCIIMode() = false;
        ok = w.Write(s, tmp.c_str());
      } else {
        write_off(s, tmp);
      }
    }
    if (!ok) throw ComputeError("cannot write '" + path + "'");
  } catch (const Standard_Failure& f) {
    std::remove(tmp.c_str());
    throw ComputeError(std::string("writing '") + path + "' failed: " +
                       (f.GetMessageString() ? f.GetMessageString() : "OCCT error"));
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw ComputeError("cannot write '" + path + "'");
  }
}

std::string shape_to_brep_string(const Shape& shape) {
  std::ostringstream o;
  BRepTools::Write(shape.shape, o);
  return o.str();
}

double file_volume(const std::string& path) {
  TopoDS_Shape s = read_shape_file(path, "");
  GProp_GProps g;
  BRepGProp::VolumeProperties(s, g, 1e-10);
  return g.Mass();
}

}  // namespace sweep::occt
