"""The hostile and careless-user corpus of `bhnsid sequence`, as data (replayed by
test_hostile.py). Each case: a kind, a name, what is prepared in a fresh folder W, the command's
arguments, and the expected exit code and words of its one error line. Every case is also checked
for no Python traceback, no file named PWNED* created, nothing written or deleted in W/victim
(which every link points into), one line on stderr when it fails, and an end within its time.

Templates in strings: {W} the case's folder, {SEQ} W/seq (the default --output), {RUN} the first
run directory in it, {FAKE} a stand-in bhnsid (tests/sequence/fake_bhnsid.py), {BHNSID} the
build's, {SRC} the source tree. Preparation steps, in order:
  ("write", PATH, TEXT)   ("mkdir", PATH)   ("link", PATH, TARGET)   ("fifo", PATH)
  ("first_run",)          the default sequence run once (two converged runs in SEQ)
  ("lock", PATH)          the runner holds an flock on PATH during the case"""

from checklist import TINY_SPEC  # noqa: E402  (test_hostile.py runs from this folder)

SPEC = TINY_SPEC + "  threads: 1\n"
RUN = "{SEQ}/grid0_n24_dx0.16/xa0.25/rho0.08"
DEFAULT = ["{W}/spec.yaml", "--output", "{SEQ}", "--bhnsid", "{FAKE}"]
PWN = "$(touch PWNED)"


def spec(**changes):
    """SPEC with some lines replaced: key=value for `  key: value` (None removes the line)."""
    lines = []
    for line in SPEC.splitlines():
        k = line.strip().split(":")[0]
        if k in changes:
            if changes[k] is not None:
                lines.append(f"  {k}: {changes[k]}")
            continue
        lines.append(line)
    return "\n".join(lines) + "\n" + "".join(f"  {k}: {v}\n" for k, v in changes.items()
                                              if v is not None and k not in SPEC)


def case(kind, name, rc, says="", args=None, extra=(), prepare=(), text=SPEC, **kw):
    return dict(kind=kind, name=name, rc=rc, says=says, argv=list(args if args is not None else DEFAULT) + list(extra),
                prepare=list(prepare), spec=text, **kw)


def slurm(*extra):
    return ["--slurm", "--emit-only"] + list(extra)


CASES = [
    # Names that reach a shell, a script or a terminal line.
    case("names", "output_with_quote_and_space", 0, args=["{W}/spec.yaml", "--output", "{W}/Bob's runs", "--bhnsid", "{FAKE}"]),
    case("names", "output_with_command_substitution", 0, args=["{W}/spec.yaml", "--output", "{W}/x" + PWN, "--bhnsid", "{FAKE}"]),
    case("names", "output_with_backticks", 0, args=["{W}/spec.yaml", "--output", "{W}/`touch PWNED`", "--bhnsid", "{FAKE}"]),
    case("names", "output_with_semicolons", 0, args=["{W}/spec.yaml", "--output", "{W}/a;touch PWNED;b", "--bhnsid", "{FAKE}"]),
    case("names", "output_with_newline", 0, args=["{W}/spec.yaml", "--output", "{W}/a\nb", "--bhnsid", "{FAKE}"]),
    case("names", "spec_named_like_a_command_default_output", 0, args=["a';touch PWNED;'.yaml", "--bhnsid", "{FAKE}"],
         prepare=[("write", "a';touch PWNED;'.yaml", SPEC)]),
    case("names", "spec_named_with_newline_bad_content", 2, "\\x0a", args=["{W}/x\ny.yaml", "--bhnsid", "{FAKE}"],
         prepare=[("write", "x\ny.yaml", "sequence: [1]\n")]),
    case("names", "base_named_like_a_command", 0, text=spec(base="\"b'$(touch PWNED).yaml\""),
         prepare=[("write", "b'$(touch PWNED).yaml", "grid: {n: 24}\n")]),
    case("names", "set_value_with_command_substitution", 0, text=spec(set="{run.note: '" + PWN + "'}")),
    case("names", "set_value_with_newline", 2, "control characters", text=spec(set='{run.note: "a\\nb"}')),
    case("names", "slurm_output_with_quote_and_command", 0, args=["{W}/spec.yaml", "--output", "{W}/Bob's " + PWN,
                                                                  "--bhnsid", "{FAKE}"] + slurm(), paste=True),
    case("names", "slurm_output_with_percent", 0, args=["{W}/spec.yaml", "--output", "{W}/100%a", "--bhnsid", "{FAKE}"]
         + slurm(), paste=True),
    case("names", "slurm_output_with_backslash", 2, "--output", args=["{W}/spec.yaml", "--output", "{W}/a\\b",
                                                                      "--bhnsid", "{FAKE}"] + slurm()),
    case("names", "slurm_output_with_newline", 2, "--output", args=["{W}/spec.yaml", "--output", "{W}/a\nb",
                                                                    "--bhnsid", "{FAKE}"] + slurm()),
    case("names", "slurm_submission_of_a_quoted_directory", 0, args=["{W}/spec.yaml", "--output", "{W}/Bob's runs",
                                                                     "--bhnsid", "{FAKE}", "--slurm"], sbatch="ok"),
    # SLURM options: only SLURM's own syntax reaches an #SBATCH line.
    case("slurm_options", "partition_newline_and_directive", 2, "--partition",
         extra=slurm("--partition", "short\n#SBATCH --wrap=touch PWNED")),
    case("slurm_options", "partition_semicolon", 2, "--partition", extra=slurm("--partition", "x;touch PWNED")),
    case("slurm_options", "partition_command_substitution", 2, "--partition", extra=slurm("--partition", PWN)),
    case("slurm_options", "partition_blank", 2, "--partition", extra=slurm("--partition", "a b")),
    case("slurm_options", "partition_empty", 2, "--partition", extra=slurm("--partition", "")),
    case("slurm_options", "account_newline_command", 2, "--account", extra=slurm("--account", "acc\ntouch PWNED")),
    case("slurm_options", "account_quote", 2, "--account", extra=slurm("--account", "a'b")),
    case("slurm_options", "time_newline_command", 2, "--time", extra=slurm("--time", "1:00\ntouch PWNED")),
    case("slurm_options", "time_four_fields", 2, "--time", extra=slurm("--time", "1:00:00:00")),
    case("slurm_options", "time_word", 2, "--time", extra=slurm("--time", "tomorrow")),
    case("slurm_options", "time_negative", 2, "--time", extra=slurm("--time", "-1")),
    case("slurm_options", "valid_options_accepted", 0,
         extra=slurm("--partition", "short,long", "--time", "1-12:00:00", "--account", "proj.a-1")),
    case("slurm_options", "partition_without_slurm", 2, "only with --slurm", extra=["--partition", "short"]),
    case("slurm_options", "sbatch_answers_a_command", 2, "not a job id", extra=["--slurm"], sbatch="evil"),
    # Links where the sequence writes or removes.
    case("links", "checkpoints_folder_linked_elsewhere", 2, "checkpoints", prepare=[
        ("first_run",), ("link", RUN + "/checkpoints", "{W}/victim")]),
    case("links", "run_log_linked_elsewhere", 2, "rho0.08.out", prepare=[
        ("mkdir", "seq/grid0_n24_dx0.16/xa0.25"), ("write", "seq/.bhnsid-sequence", "x\n"),
        ("link", "seq/grid0_n24_dx0.16/xa0.25/rho0.08.out", "{W}/victim/data.txt")]),
    case("links", "sequence_json_partial_linked_elsewhere", 0, prepare=[
        ("write", "seq/.bhnsid-sequence", "x\n"), ("link", "seq/sequence.json.partial", "{W}/victim/data.txt")]),
    case("links", "lock_file_linked_elsewhere", 2, "lock", prepare=[
        ("write", "seq/.bhnsid-sequence", "x\n"), ("link", "seq/.bhnsid-sequence.lock", "{W}/victim/data.txt")]),
    case("links", "marker_linked_elsewhere", 2, ".bhnsid-sequence", prepare=[
        ("mkdir", "seq"), ("link", "seq/.bhnsid-sequence", "{W}/victim/data.txt")]),
    case("links", "grid_folder_linked_elsewhere", 2, "grid0_n24_dx0.16", prepare=[
        ("write", "seq/.bhnsid-sequence", "x\n"), ("link", "seq/grid0_n24_dx0.16", "{W}/victim")]),
    case("links", "run_directory_linked_elsewhere", 2, "rho0.08", prepare=[
        ("mkdir", "seq/grid0_n24_dx0.16/xa0.25"), ("write", "seq/.bhnsid-sequence", "x\n"),
        ("link", "seq/grid0_n24_dx0.16/xa0.25/rho0.08", "{W}/victim")]),
    case("links", "result_file_linked_elsewhere", 2, "sequence.json", prepare=[
        ("write", "seq/.bhnsid-sequence", "x\n"), ("link", "seq/sequence.json", "{W}/victim/data.txt")]),
    case("links", "figure_linked_elsewhere", 2, "eb.png", prepare=[
        ("write", "seq/.bhnsid-sequence", "x\n"), ("link", "seq/eb.png", "{W}/victim/data.txt")]),
    case("links", "checkpoint_file_linked_elsewhere", 2, "checkpoint.000001", prepare=[
        ("first_run",), ("mkdir", RUN + "/checkpoints"),
        ("link", RUN + "/checkpoints/checkpoint.000001", "{W}/victim/checkpoint.000001")]),
    case("links", "slurm_folder_linked_elsewhere", 2, "slurm", extra=slurm(), prepare=[
        ("write", "seq/.bhnsid-sequence", "x\n"), ("link", "seq/slurm", "{W}/victim")]),
    case("links", "summary_linked_elsewhere", 2, "summary.json", prepare=[
        ("mkdir", RUN), ("write", "seq/.bhnsid-sequence", "x\n"), ("link", RUN + "/summary.json", "{W}/victim/summary.json")]),
    case("links", "output_itself_a_link_is_followed", 0, args=["{W}/spec.yaml", "--output", "{W}/out", "--bhnsid", "{FAKE}"],
         prepare=[("mkdir", "real"), ("link", "out", "{W}/real")], keeps=["real/sequence.json"]),
    case("links", "user_notes_in_checkpoints_kept", 0, extra=["--retry-failed"], prepare=[
        ("first_run",), ("mkdir", RUN + "/checkpoints"), ("write", RUN + "/checkpoints/notes.txt", "mine"),
        ("write", RUN + "/checkpoints/checkpoint.000007", "old")], keeps=[RUN.replace("{SEQ}", "seq") + "/checkpoints/notes.txt"],
         absent=[RUN.replace("{SEQ}", "seq") + "/checkpoints/checkpoint.000007"]),
    # Special files where a regular file belongs.
    case("special_files", "spec_is_a_fifo", 2, "not a regular file", args=["{W}/pipe.yaml"], prepare=[("fifo", "pipe.yaml")]),
    case("special_files", "spec_is_dev_zero", 2, "not a regular file", args=["/dev/zero", "--output", "{SEQ}"]),
    case("special_files", "spec_is_a_directory", 2, "not a regular file", args=["{W}", "--output", "{SEQ}"]),
    case("special_files", "spec_missing", 2, "No such file", args=["{W}/nowhere.yaml"]),
    case("special_files", "summary_is_a_fifo", 2, "summary.json", prepare=[
        ("mkdir", RUN), ("write", "seq/.bhnsid-sequence", "x\n"), ("fifo", RUN + "/summary.json")]),
    case("special_files", "run_log_is_a_fifo", 2, "rho0.08.out", prepare=[
        ("mkdir", "seq/grid0_n24_dx0.16/xa0.25"), ("write", "seq/.bhnsid-sequence", "x\n"),
        ("fifo", "seq/grid0_n24_dx0.16/xa0.25/rho0.08.out")]),
    case("special_files", "timers_is_a_fifo", 2, "timers.tsv", prepare=[
        ("mkdir", RUN), ("write", "seq/.bhnsid-sequence", "x\n"), ("fifo", RUN + "/timers.tsv")]),
    case("special_files", "task_list_is_a_fifo", 2, "--task", extra=["--task", "{W}/tasks:0"], prepare=[("fifo", "tasks")]),
    case("special_files", "base_is_a_fifo", 2, "not a regular file", text=spec(base="pipe.yaml"), prepare=[("fifo", "pipe.yaml")]),
    case("special_files", "output_is_a_file", 2, "not a directory", args=["{W}/spec.yaml", "--output", "{W}/spec.yaml",
                                                                          "--bhnsid", "{FAKE}"]),
    case("special_files", "output_is_dev_null", 2, "not a directory", args=["{W}/spec.yaml", "--output", "/dev/null",
                                                                            "--bhnsid", "{FAKE}"]),
    case("special_files", "spec_of_ten_megabytes", 2, "more than", text="#" * (10 << 20) + "\n"),
    # Options a careless user types.
    case("options", "jobs_zero", 2, "--jobs", extra=["--jobs", "0"]),
    case("options", "jobs_not_a_number", 2, "--jobs", extra=["--jobs", "abc"]),
    case("options", "jobs_huge", 2, "--jobs", extra=["--jobs", "100000"]),
    case("options", "output_empty", 2, "expected a directory name", args=["{W}/spec.yaml", "--output", "", "--bhnsid", "{FAKE}"]),
    case("options", "bhnsid_missing_with_another_on_path", 2, "--bhnsid", args=["{W}/spec.yaml", "--output", "{SEQ}",
                                                                                "--bhnsid", "{W}/nowhere"], path_bhnsid=True),
    case("options", "bhnsid_a_directory", 2, "not an executable", args=["{W}/spec.yaml", "--bhnsid", "{W}"]),
    case("options", "bhnsid_not_executable", 2, "not an executable", args=["{W}/spec.yaml", "--bhnsid", "{W}/spec.yaml"]),
    case("options", "emit_only_without_slurm", 2, "--emit-only", extra=["--emit-only"]),
    case("options", "slurm_and_reduce_only", 2, "exclude", extra=["--slurm", "--reduce-only"]),
    case("options", "unknown_option", 2, "--frobnicate", extra=["--frobnicate"]),
    case("options", "no_arguments", 2, "file", args=[]),
    case("options", "task_list_missing", 2, "--task", extra=["--task", "nowhere:0"]),
    case("options", "task_index_negative", 2, "--task", extra=["--task", "{W}/tasks:-1"],
         prepare=[("write", "tasks", "grid0_n24_dx0.16/xa0.25/rho0.08\n")]),
    case("options", "foreign_folder_as_output", 2, "not a sequence directory", prepare=[("write", "seq/thesis.tex", "x")]),
    # Sequence files.
    case("specs", "nan_target", 2, "sequence.targets[0]", text=spec(targets="[.nan]")),
    case("specs", "inf_rho_max", 2, "sequence.rho_max[1]", text=spec(rho_max="[0.08, .inf]")),
    case("specs", "grid_n_not_an_integer", 2, "sequence.grids[0].n", text=spec(grids="[{n: 64.5, dx: 0.1}]")),
    case("specs", "count_inf", 2, "count", text=spec(rho_max="{from: 0.05, to: 0.1, count: inf}")),
    case("specs", "count_1e12", 2, "count", text=spec(rho_max="{from: 0.05, to: 0.1, count: 1e12}")),
    case("specs", "count_1_0e_plus_12", 2, "count", text=spec(rho_max="{from: 0.05, to: 0.1, count: 1.0e+12}")),
    case("specs", "not_utf8", 2, "UTF-8", text=SPEC.encode() + b"# \xff\xfe\n"),
    case("specs", "alias_bomb", 2, "aliases", text="a: &a [x, x, x, x, x, x, x, x, x]\n" + "".join(
        f"{chr(98 + i)}: &{chr(98 + i)} [*{chr(97 + i)}, *{chr(97 + i)}, *{chr(97 + i)}, *{chr(97 + i)}, *{chr(97 + i)}, "
        f"*{chr(97 + i)}, *{chr(97 + i)}, *{chr(97 + i)}, *{chr(97 + i)}]\n" for i in range(8)) + SPEC),
    case("specs", "a_million_rho_max", 2, "more than", text=spec(rho_max="[" + ", ".join(["0.1"] * 1000000) + "]")),
    case("specs", "201_rho_max", 2, "at most 200", text=spec(rho_max="[" + ", ".join(
        str(0.05 + i * 1e-4) for i in range(201)) + "]")),
    case("specs", "too_many_runs", 2, "at most 5000", text=spec(
        x_a="{from: -0.5, to: 0.5, count: 200}", rho_max="{from: 0.05, to: 0.1, count: 200}")),
    case("specs", "duplicate_key", 2, "duplicate key", text=SPEC + "  mass_ratio: 2.0\n"),
    case("specs", "unknown_key", 2, "sequence.xa", text=SPEC + "  xa: [0.1]\n"),
    case("specs", "missing_key", 2, "sequence.targets: missing", text=spec(targets=None)),
    case("specs", "yaml_tag", 2, "tag", text=spec(mass_ratio="!!str 1.0")),
    case("specs", "deep_nesting", 2, "nested deeper", text="sequence: " + "[" * 60000 + "\n"),
    case("specs", "empty_file", 2, "section 'sequence'", text=""),
    case("specs", "a_list_not_a_mapping", 2, "section 'sequence'", text="- 1\n- 2\n"),
    case("specs", "two_documents", 2, "several YAML documents", text=SPEC + "---\n" + SPEC),
    case("specs", "real_overflows", 2, "overflows", text=spec(mass_ratio="1e400")),
    case("specs", "hexadecimal_n", 2, "grids[0].n", text=spec(grids="[{n: 0x20, dx: 0.1}]")),
    case("specs", "huge_integer_n", 2, "digits", text=spec(grids="[{n: " + "9" * 40 + ", dx: 0.1}]")),
    case("specs", "threads_yes", 2, "sequence.threads", text=spec(threads="true")),
    case("specs", "set_of_a_key_the_sequence_sets", 2, "set by the sequence", text=spec(set="{grid.n: 64}")),
    case("specs", "set_key_without_section", 2, "section.key", text=spec(set="{loop_cycles: 1}")),
    case("specs", "set_value_a_mapping", 2, "sequence.set.grid.max_levels", text=spec(set="{grid.max_levels: {a: 1}}")),
    case("specs", "mass_ratio_zero", 2, "sequence.mass_ratio", text=spec(mass_ratio="0")),
    case("specs", "x_a_outside", 2, "sequence.x_a[0]", text=spec(x_a="[1.5]")),
    case("specs", "x_a_twice", 2, "listed twice", text=spec(x_a="[0.25, 0.25]")),
    case("specs", "values_differ_in_the_7th_digit", 0, text=spec(x_a="[0.25, 0.2500001]"),
         keeps=["seq/grid0_n24_dx0.16/xa0.25/rho0.08", "seq/grid0_n24_dx0.16/xa0.2500001/rho0.08"]),
    case("specs", "binary_garbage", 2, "spec.yaml", text=b"\x00\x01sequence\x00: [\x80]\n"),
    case("specs", "key_of_a_thousand_characters", 2, "a key of 1000 characters", text=SPEC + "  " + "k" * 1000 + ": 1\n"),
    case("specs", "windows_line_ends_and_a_bom", 0, text=b"\xef\xbb\xbf" + SPEC.replace("\n", "\r\n").encode()),
    case("specs", "tab_indentation", 2, "spec.yaml:", text=SPEC.replace("  mass_ratio", "\tmass_ratio")),
    case("specs", "override_the_core_refuses", 2, "bhnsid check refuses", timeout=30,
         args=["{W}/spec.yaml", "--output", "{SEQ}"], absent=["seq/grid0_n24_dx0.16"],
         text=spec(base="{SRC}/parfiles/quickstart.yaml", set="{multigrid.loop_cycles: banana}")),
    # Resources: a full disk, closed output streams.
    case("resources", "file_size_limit_on_results", 2, "File too large", fsize=2000, absent=["seq/*.partial"]),
    case("resources", "file_size_limit_at_once", 2, "File too large", fsize=1),
    # Resumed: the lock's holder line, when it is the write refused, named no file.
    case("resources", "file_size_limit_on_resume_names_the_file", 2, ": cannot write", fsize=1,
         prepare=[("first_run",)]),
    case("resources", "stdout_closed", 0, close_stdout=True, keeps=["seq/sequence.json"]),
    case("resources", "stdout_and_stderr_closed", 0, close_stdout=True, close_stderr=True, keeps=["seq/sequence.json"]),
    # Signals.
    case("signals", "sigterm_mid_run", 143, signal=("TERM", False), env={"FAKE_SLEEP": "30"}),
    case("signals", "ctrl_c_to_the_group", 130, signal=("INT", True), env={"FAKE_SLEEP": "30"}),
    case("signals", "sighup_mid_run", 129, signal=("HUP", False), env={"FAKE_SLEEP": "30"}),
    case("signals", "sighup_ignored_under_nohup", 0, signal=("HUP", False), nohup=True, env={"FAKE_SLEEP": "1"}),
    # Two at once.
    case("concurrency", "second_pool_while_the_first_holds_the_lock", 2, "another bhnsid sequence",
         prepare=[("write", "seq/.bhnsid-sequence", "x\n"), ("lock", "seq/.bhnsid-sequence.lock")]),
]
