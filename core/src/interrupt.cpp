#include "bhnsid/core/interrupt.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <initializer_list>

namespace bhnsid::core {

namespace {

volatile std::sig_atomic_t received = 0;
volatile std::sig_atomic_t child = 0;

extern "C" void on_stop_signal(int signal) {
  // The child runs in a process group of its own, so the terminal's signal reaches it only
  // through here: once for the first signal, once more for the second.
  if (child > 0) ::kill(static_cast<pid_t>(child), signal);
  if (received != 0) ::_exit(128 + signal);
  received = signal;
  static const char message[] =
      "\nbhnsid: stopping at the next safe point and keeping the last state (send the signal again to exit at once)\n";
  // Only async-signal-safe calls here; a failed write to a closed terminal changes nothing.
  const ssize_t ignored = ::write(2, message, sizeof message - 1);
  (void)ignored;
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // One handler at a time: a SIGTERM arriving inside the SIGINT handler then counts as the second.
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, signal);
  action.sa_flags = SA_RESTART;
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    // A signal ignored when we started stays ignored: `nohup bhnsid run ... &` survives the logout.
    if (sigaction(signal, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(signal, &action, nullptr);
  }
  std::signal(SIGPIPE, SIG_IGN);
}

void forward_interrupts_to(int pid) { child = pid; }

int interrupt_signal() { return received; }

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

}  // namespace bhnsid::core
