#pragma once
// Shared helpers for the core's variety tests: an entity from its spec JSON, expressions in t, and
// a path that is no screw.
#include <string>

#include "sweep/entity.hpp"
#include "sweep/spec.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep_test {

inline sweep::Expr texpr(const char* text) { return sweep::Expr::parse(text, {"t"}); }

/// The entity of `entity_json` (a spec's "entity" object, placement applied).
inline sweep::EntityPtr entity_of(const std::string& entity_json) {
  const std::string text = R"({"sweep": 1, "entity": )" + entity_json +
                           R"(, "motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0],
                              "direction": [0, 0, 1], "range": [0, 1]}]}})";
  return sweep::make_entity(sweep::parse_spec(text, "").entity);
}

/// A path that is no screw: along (t, t^2, sin t) while turning about an axis that tilts with t,
/// t in [0, 2].
inline sweep::PathMotion wandering_path() {
  const sweep::Expr tr[3] = {texpr("t"), texpr("t^2"), texpr("sin(t)")};
  return sweep::PathMotion(0, 2, tr, {sweep::PathRotation{{texpr("0.3"), texpr("1"), texpr("t")}, texpr("0.7*t")}});
}

}  // namespace sweep_test
