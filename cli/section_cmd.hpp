#pragma once
/// `sweepvol section ...` and the SVG drawing of `sweepvol varieties --svg`.
#include <memory>
#include <string>
#include <vector>

#include "occt_bridge/sweeper.hpp"

/// `sweepvol section SPEC --z Z1,Z2,... [--svg F.svg] [-o S.json] [--set PATH=VALUE]...`: argv[0] is
/// "section". Returns the process exit code; throws sweep::InputError (exit 2) for bad input and
/// sweep::ComputeError (exit 3) when a section fails.
int sweep_section_main(int argc, char** argv);

/// Refuses (InputError naming `option`) a drawing path that does not end in ".svg".
void sweep_check_svg_path(const std::string& path, const char* option);

/// Writes the drawing of the last stage's variety faces to `path` (atomically); `ids` gives each
/// face's variety as an index into `varieties` (-1 when unknown).
void sweep_write_varieties_svg(const std::string& path, const sweep::Spec& spec, const sweep::occt::Shape& faces,
                               const std::vector<int>& ids, const std::vector<sweep::occt::Variety>& varieties);
