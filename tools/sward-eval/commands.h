// The commands of sward-eval, each a tool of its own behind a command word (main.cpp dispatches on it).
#pragma once

int stereoMain(int argc, char** argv);   // stereo.cpp: `sward-eval [stereo] DATASET`
int flowMain(int argc, char** argv);     // flow.cpp: `sward-eval flow DATASET`
int odometryMain(int argc, char** argv); // odometry.cpp: `sward-eval odometry DATASET`
int lookMain(int argc, char** argv);     // look.cpp: `sward-eval look DATASET`
