// A shape split by edges (OCCT's splitter), polling the stop request.
#include <BRepAlgoAPI_Splitter.hxx>
#include <TopTools_ListOfShape.hxx>

#include "base/internal.hpp"
#include "base/stop.hpp"

namespace sweep::occt {

TopoDS_Shape split_by_edges(const TopoDS_Shape& shape, const TopTools_ListOfShape& tools, double fuzzy,
                            SplitMode mode) {
  BRepAlgoAPI_Splitter splitter;
  TopTools_ListOfShape args;
  args.Append(shape);
  splitter.SetArguments(args);
  splitter.SetTools(tools);
  if (mode == SplitMode::Parallel) splitter.SetRunParallel(true);
  else splitter.SetNonDestructive(true);
  splitter.SetFuzzyValue(fuzzy);
  splitter.Build(stop_range());
  check_stop();
  if (!splitter.IsDone() || splitter.HasErrors()) return {};
  return splitter.Shape();
}

}  // namespace sweep::occt
