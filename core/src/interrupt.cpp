#include "bhnsid/core/interrupt.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <initializer_list>

namespace bhnsid::core {

namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void on_stop_signal(int signal) {
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
  // No SA_RESTART: a blocking wait (validate's waitpid on a level run) returns EINTR, so the signal
  // can be passed on to the child.
  action.sa_flags = 0;
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal, &action, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
}

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
