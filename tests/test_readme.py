"""Every ``softpad`` command line in the README's code blocks runs (quick variants for long ones)."""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path

import pytest

from softpad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]

#: Long commands and the quick variant the test runs instead (same options, smaller job).
QUICK = {
    "run --objects object-5 --png run.png": "run --objects object-5 --png run.png --hold-s 1",
    "run --objects charger --json": "run --objects charger --json --hold-s 1",
    "run --objects object-5 --record run.mcap": "run --objects object-5 --record run.mcap "
    "--hold-s 1",
    "box monitor --foxglove": "box monitor --foxglove --port 0 --count 20",
    "box monitor": "box monitor --count 20",
    "trials --objects banana,toy --trials 2": "trials --objects banana --trials 1 --workers 1 "
    "--hold-s 1 --no-progress",
    "fem sweep --model yeoh --json": "fem sweep --model yeoh --json --mesh coarse --points 3",
    "fem design --models neo-hookean --png design.png": "fem design --models neo-hookean "
    "--png design.png --mesh coarse --values-mm 1.5,2",
    "fem chamber": "fem chamber --mesh coarse --masses-g 12.6",
    "fem response --out response.npz": "fem response --out response.npz --mesh coarse "
    "--pressures-kpa 1.1 --no-convergence --no-progress",
    "pad map --force-n 0.1236 --footprint-mm 42,31 --png map.png": "pad map --force-n 0.1236 "
    "--footprint-mm 42,31 --png map.png --step-mm 10",
    "bench": "bench --only planning --quick",
    "design --example thesis-set --quick": "design --example blocks --quick --grid 2x3 "
    "--hold-s 0.5 --no-cache --workers 1 --no-progress",
    "design --example thesis-set --quick --json --png pareto.png --csv designs.csv": "design "
    "--example blocks --quick --grid 2x3 --json --png pareto.png --csv designs.csv --hold-s 0.5 "
    "--no-cache --workers 1 --no-progress",
    "compare --seeds 0-19 --json": "compare --seeds 0 --json --objects banana --trials 1 "
    "--workers 1 --idle-hours 0.01 --no-progress",
}
#: Commands not run, with the reason.
SKIP = {
    "demo --out report": "the main job (55 MuJoCo trials, minutes); `make demo` runs it",
    "box serve --sim": "serves until Ctrl-C on the fixed port 7447; tests/box/test_daemon.py serves",
    "run --box zenoh://127.0.0.1:7447 --objects object-5": "needs the daemon above; "
    "tests/harness/test_remote.py runs the loop through a served box",
    "ros node --box sim:// --place object-5": "needs a roscore; tests/ros runs it against one",
    "sim arm-node --port 5757": "needs a roscore; tests/ros runs it against one",
    "compare --merge a.json --merge b.json --png both.png": "needs two saved comparisons; "
    "tests/trials/test_compare.py merges two it writes",
    "run --robot ros1:// --box zenoh://127.0.0.1:5757 --objects object-5": "needs a roscore and "
    "the arm node; tests/ros runs it",
}


def readme_commands() -> list[str]:
    """The ``softpad`` command lines of the README's code blocks, without comments."""
    text = (ROOT / "README.md").read_text()
    out = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        for line in block.splitlines():
            words = shlex.split(line, comments=True)
            if words and words[0].endswith("softpad"):
                out.append(shlex.join(words[1:]))
    return out


def test_the_readme_has_commands_and_every_variant_is_quoted() -> None:
    commands = readme_commands()
    assert len(commands) >= 15
    for key in list(QUICK) + list(SKIP):
        assert key in commands, key


@pytest.mark.parametrize("command", readme_commands())
def test_readme_command_runs(command: str, tmp_path: Path, monkeypatch, capsys) -> None:
    if command in SKIP:
        pytest.skip(SKIP[command])
    (tmp_path / "examples").mkdir()
    for name in ("frame.csv", "site.toml"):
        shutil.copy(ROOT / "examples" / name, tmp_path / "examples" / name)
    monkeypatch.chdir(tmp_path)
    if "run.mcap" in command and "--record" not in command:  # a recording made by the README
        assert main(["run", "--objects", "object-5", "--record", "run.mcap", "--hold-s", "1"]) == 0
    argv = shlex.split(QUICK.get(command, command))
    words = [w for w in argv if w not in (">",)]
    redirect = None
    if ">" in argv:
        redirect = argv[argv.index(">") + 1]
        words = argv[: argv.index(">")]
    try:
        code = main(words)
    except SystemExit as exc:  # --help
        code = int(exc.code or 0)
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "Traceback" not in captured.err
    if redirect:
        assert "complete" in captured.out
