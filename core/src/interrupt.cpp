#include "bhnsid/core/interrupt.hpp"

#include <unistd.h>

#include <ctime>

#include <csignal>
#include <cstdio>
#include <initializer_list>

namespace bhnsid::core {

namespace {

volatile std::sig_atomic_t received = 0;
volatile std::sig_atomic_t child = 0;
// Who sent the first stopping signal, and when (written by the handler alone, which runs one at a time).
pid_t first_sender = 0;
bool first_from_process = false;
struct timespec first_time {};

// A copy of a request already taken: `timeout` signals its child and then the child's process group,
// a batch system signals every process of a job (validate's level run then hears it from the system
// and from validate). Each arrives within microseconds, sent by a process; a person's second Ctrl-C
// comes from the terminal (SI_KERNEL) and always counts.
constexpr long duplicate_window_ns = 500'000'000;

bool sent_by_process(const siginfo_t* info) {
  return info && (info->si_code == SI_USER || info->si_code == SI_QUEUE || info->si_code == SI_TKILL);
}

bool is_duplicate(int signal, const siginfo_t* info) {
  if (signal != received || !sent_by_process(info)) return false;
  // A parent that passes on the stop its own process group received (the terminal's Ctrl-C reaching
  // both) repeats that request; so does the sender of the first signal sending it again.
  const pid_t parent = ::getppid();
  const bool same_request =
      info->si_pid == parent || (first_from_process && (info->si_pid == first_sender || first_sender == parent));
  if (!same_request) return false;
  struct timespec now {};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  const long elapsed = (now.tv_sec - first_time.tv_sec) * 1'000'000'000L + (now.tv_nsec - first_time.tv_nsec);
  return elapsed < duplicate_window_ns;
}

extern "C" void on_stop_signal(int signal, siginfo_t* info, void*) {
  if (received != 0 && is_duplicate(signal, info)) return;
  // The child runs in a process group of its own, so the terminal's signal reaches it only
  // through here: once for the first signal, once more for the second.
  if (child > 0) ::kill(static_cast<pid_t>(child), signal);
  if (received != 0) ::_exit(128 + signal);
  first_from_process = sent_by_process(info);
  first_sender = info ? info->si_pid : 0;
  ::clock_gettime(CLOCK_MONOTONIC, &first_time);
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
  action.sa_sigaction = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // One handler at a time: a SIGTERM arriving inside the SIGINT handler then counts as the second.
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, signal);
  action.sa_flags = SA_RESTART | SA_SIGINFO;
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
