"""The front page and the command examples.

Every ``softpad`` command line in the bash code blocks of README.md, docs/quickstart.md and
docs/cli.md runs (quick variants for long ones, a few skipped with the reason); README.md fits
a screen and starts with the two set-up commands; its headline figures come from
docs/results.md once ``make results`` has written it."""

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
    "validate": "validate --placements 2 --no-progress",
    "trials --objects object-5 --trials 2 --randomize --json": "trials --objects object-5 "
    "--trials 1 --randomize --json --workers 1 --hold-s 1 --no-progress",
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
    "calibrate session.mcap --json": "needs recordings of known loads on a pad; "
    "tests/trials/test_calibrate.py records them on a simulated pad and fits them",
    "results --force": "reruns every quoted result (about 30 min) into docs/results.md; "
    "tests/cli/test_results_cli.py runs --quick",
}


#: Where the command examples live.
DOCS = ("README.md", "docs/quickstart.md", "docs/cli.md")
#: The front page fits a screen or two (issue 36).
README_MAX_LINES = 120


def doc_commands(doc: str) -> list[str]:
    """The ``softpad`` command lines of a Markdown file's bash code blocks, without comments."""
    text = (ROOT / doc).read_text()
    out = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        for line in block.splitlines():
            words = shlex.split(line, comments=True)
            if words and words[0].endswith("softpad"):
                out.append(shlex.join(words[1:]))
    return out


def documented_commands() -> list[str]:
    """Every documented ``softpad`` command line, once, in the order of :data:`DOCS`."""
    return list(dict.fromkeys(c for doc in DOCS for c in doc_commands(doc)))


def test_the_docs_have_commands_and_every_variant_is_quoted() -> None:
    commands = documented_commands()
    assert len(commands) >= 40
    for key in list(QUICK) + list(SKIP):
        assert key in commands, f"{key!r} is in QUICK or SKIP but in none of {DOCS}"
    assert doc_commands("README.md"), "README.md shows no softpad command"


def test_the_readme_fits_a_screen_and_starts_with_the_two_commands() -> None:
    text = (ROOT / "README.md").read_text()
    lines = text.splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines (limit 120)"
    first = re.search(r"```bash\n(.*?)```", text, flags=re.S)
    assert first is not None
    commands = [ln.split("#")[0].strip() for ln in first.group(1).splitlines()]
    assert commands[:2] == ["make demo", "make test"], commands


def test_every_doc_the_readme_links_exists() -> None:
    text = (ROOT / "README.md").read_text()
    links = re.findall(r"\]\(([^)#]+\.md)(?:#[^)]*)?\)", text)
    assert len(links) >= 10
    missing = [link for link in links if link != "docs/results.md" and not (ROOT / link).is_file()]
    assert not missing, missing


def headline_figures() -> list[str]:
    """The README's headline figures: the bold spans with a digit in its figures section."""
    text = (ROOT / "README.md").read_text()
    section = text.split("## Headline figures", 1)[1].split("\n## ", 1)[0]
    return [f for f in re.findall(r"\*\*(.+?)\*\*", section) if re.search(r"\d", f)]


def test_the_readme_quotes_only_figures_of_docs_results() -> None:
    """Issue 33: README.md quotes only figures that ``softpad results`` wrote."""
    figures = headline_figures()
    assert len(figures) >= 3
    results = ROOT / "docs" / "results.md"
    if not results.is_file():
        pytest.skip("docs/results.md not written yet (make results)")
    text = results.read_text()
    absent = [f for f in figures if f not in text]
    assert not absent, (
        f"README.md's headline figures {absent} are not in docs/results.md: quote the figures "
        "of docs/results.md (and its commit) in README.md"
    )


@pytest.mark.parametrize("command", documented_commands())
def test_documented_command_runs(command: str, tmp_path: Path, monkeypatch, capsys) -> None:
    if command in SKIP:
        pytest.skip(SKIP[command])
    (tmp_path / "examples").mkdir()
    for name in ("frame.csv", "site.toml"):
        shutil.copy(ROOT / "examples" / name, tmp_path / "examples" / name)
    monkeypatch.chdir(tmp_path)
    if "run.mcap" in command and "--record" not in command:  # a recording made by the docs
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
