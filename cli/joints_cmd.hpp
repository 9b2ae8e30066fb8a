#pragma once
/// `sweepvol joints ...`: argv[0] is "joints". Returns the process exit code.
int sweep_joints_main(int argc, char** argv);
