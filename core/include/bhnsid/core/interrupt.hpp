#pragma once
// SIGINT, SIGTERM and SIGHUP stop a run at its next safe point rather than killing it: the first
// signal sets a flag that the core polls between schedule entries (and long loops, such as the
// multigrid's cycles, poll between iterations); the run then keeps its last state, writes
// summary.json with "status": "interrupted" and exits 128 + the signal (130, 143, 129). A second
// signal exits at once, except a copy of the first: the same signal sent by the same process, or by
// our parent passing it on, within half a second (`timeout` and batch systems deliver one request
// twice); a terminal's second Ctrl-C always counts. SIGPIPE is ignored, so output to a closed pipe
// is a failed write, never the end of a run. Installed by `run` and `validate` only; a signal that was ignored at start
// (nohup) stays ignored.
namespace bhnsid::core {

void install_interrupt_handlers();
/// While `pid` > 0 every stopping signal is also sent to that child (validate's level runs, which
/// run in their own process group so that a terminal's Ctrl-C reaches them once, through us).
void forward_interrupts_to(int pid);
/// The first stopping signal received, 0 when none.
int interrupt_signal();
/// "SIGINT", "SIGTERM", "SIGHUP" or "signal N".
const char* signal_name(int signal);

}  // namespace bhnsid::core
