// A ball along any one-parameter motion (ball_path.cpp).
#pragma once

#include <Eigen/Geometry>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <string>
#include <vector>

#include "sweep/stage_motion.hpp"

namespace sweep::occt {

/// The solid swept by the ball of radius r centred at body point c0 under motion m: the tube about
/// its centre's path closed by two half balls, fitted within fit_tol (*fit_err raised to the
/// measured error). Null, with the reason in *why, when the centre stops, the path bends tighter
/// than r, comes back within 2 r, or a build step fails. `faces`: tube, start and end half balls.
/// The tube's circles start from the projection of a direction no tangent comes near, or with
/// `rotation_minimising` (always, when no such direction exists) from the rotation minimising frame.
TopoDS_Shape ball_path_sweep(const Eigen::Vector3d& c0, double r, const StageMotion& m, double fit_tol, double size,
                             double* fit_err, std::vector<TopoDS_Face>* faces, std::string* why,
                             bool rotation_minimising = false);

}  // namespace sweep::occt
