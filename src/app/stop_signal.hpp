#pragma once
// SIGTERM and SIGUSR1 (what batch systems send before a time limit) ask the
// run to write a checkpoint and stop cleanly at the next chance.
namespace gs {

void install_stop_signals();
bool stop_requested();

}  // namespace gs
