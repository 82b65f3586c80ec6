"""Every shell block of README.md and docs/*.md runs as written (issue 51).

A page's shell blocks (fences labelled ``bash``, ``sh``, ``shell`` or ``console``) run in
order with bash, in one scratch folder per page, so that a block may use the files an earlier
block of the same page wrote (``compare ... --json > a.json`` before ``compare --merge
a.json``). The folder holds what a fresh clone holds beside the docs: ``.venv`` (this
checkout's), ``src`` and ``examples``, and the scripts of ``docs/``; ``HOME`` and the caches
point into it, so no state from an earlier run answers a block.

An HTML comment just before a fence says how it runs (one or more words, comma-separated):

``<!-- docs-test: slow -->``
    minutes of work or a server: run by ``make test-slow`` (with every other block of its page,
    in order), not by ``make test``;
``<!-- docs-test: roscore -->``
    a ROS 1 master on a free loopback port is started for the block (ROS_MASTER_URI set);
``<!-- docs-test: not run: REASON -->``
    never run (``make test`` itself, an install on the box computer); the few allowed are
    listed in :data:`NOT_RUN`;
``<!-- docs-test: output -->``
    before a ``text`` fence: what the previous shell block prints; every non-blank line of it
    must appear in that block's output, ``...`` standing for any text.

A line ending in ``&`` starts a server: the block goes on once the server printed its first
line (60 s at most), and when the block ends the server gets SIGINT and must exit 130 as
docs/cli.md promises. ``set -e -o pipefail`` holds: any failing command fails the test.
An unlabelled fence whose first command looks like a shell command fails too: a block that
reads as runnable is run, or labelled ``text``.
"""

from __future__ import annotations

import dataclasses
import os
import re
import shutil
import socket
import subprocess
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = ("README.md", *sorted(str(p.relative_to(ROOT)) for p in (ROOT / "docs").glob("*.md")))
SHELL = ("bash", "sh", "shell", "console")
#: How many blocks of a page are never run (their reasons are on the page): the set-up
#: (`make demo`, `make test`: these tests are part of it), an install on the box computer, and
#: the research campaigns recorded in beat-the-thesis.md (hundreds of trials each, hours).
NOT_RUN = {
    "README.md": 1,
    "docs/quickstart.md": 2,
    "docs/hardware.md": 1,
    "docs/beat-the-thesis.md": 5,
}
#: Seconds a fast block may take, and a slow one (a bound on a hang, not a speed check).
TIMEOUT_S = {False: 600, True: 3600}
_FENCE = re.compile(
    r"(?:<!--\s*docs-test:\s*(?P<marks>.*?)\s*-->\s*\n)?^```(?P<lang>[\w-]*)[^\n]*\n(?P<body>.*?)^```",
    re.S | re.M,
)
_LOOKS_RUNNABLE = re.compile(r"^(\.venv/bin/)?(softpad|make|python3?|nice|sudo)\s")

#: Started before every block: servers (lines ending in ``&``) wait for their first line and
#: are stopped with SIGINT when the block ends (exit 130 required).
PRELUDE = r"""
set -e -o pipefail
set -m
__pids=(); __names=()
__serve() {  # __serve N COMMAND: start COMMAND, wait for its first line
    local fifo=".server$1.fifo" line fd
    rm -f "$fifo"; mkfifo "$fifo"
    eval "exec $2" > "$fifo" 2>&1 &  # exec: the signal's exit code is the server's own
    __pids+=($!); __names+=("$2")
    exec {fd}< "$fifo"
    if ! IFS= read -r -t 60 -u "$fd" line; then
        echo "docs-test: the server printed nothing within 60 s: $2" >&2; exit 1
    fi
    printf '%s\n' "$line"
    cat <&"$fd" >> ".server$1.out" &
}
__stop() {  # Ctrl-C's signal to every server; softpad's must exit 130 (docs/cli.md)
    local status=$? i code
    for i in "${!__pids[@]}"; do
        kill -INT -- "-${__pids[$i]}" 2>/dev/null || true
        for _ in $(seq 600); do  # 60 s at most, then it is killed and fails the block
            kill -0 "${__pids[$i]}" 2>/dev/null || break
            sleep 0.1
        done
        kill -KILL -- "-${__pids[$i]}" 2>/dev/null || true
        code=0; wait "${__pids[$i]}" || code=$?
        case "${__names[$i]}" in
            softpad*|.venv/bin/softpad*|*/softpad\ *)
                if [ "$code" != 130 ]; then
                    echo "docs-test: '${__names[$i]}' exited $code on SIGINT, not 130" >&2
                    status=1
                fi;;
        esac
    done
    exit $status
}
trap __stop EXIT
"""


@dataclasses.dataclass(frozen=True)
class Block:
    """A fenced block of a page: where it is, its language, text and ``docs-test`` marks."""

    page: str
    line: int
    lang: str
    text: str
    marks: tuple[str, ...] = ()

    @property
    def shell(self) -> bool:
        return self.lang in SHELL

    @property
    def slow(self) -> bool:
        return "slow" in self.marks

    @property
    def not_run(self) -> bool:
        return any(m.startswith("not run") for m in self.marks)

    @property
    def first_line(self) -> str:
        return next((ln.strip() for ln in self.text.splitlines() if ln.strip()), "")


def blocks(page: str, text: str | None = None) -> list[Block]:
    """The fenced blocks of a page (``text``: the page's text, read from disk when None)."""
    text = (ROOT / page).read_text() if text is None else text
    out = []
    for m in _FENCE.finditer(text):
        words = (m.group("marks") or "").strip()
        parts = [words] if words.startswith("not run") else words.split(",")
        marks = tuple(w.strip() for w in parts if w.strip())
        line = text.count("\n", 0, m.start("lang")) + 1
        out.append(Block(page, line, m.group("lang"), m.group("body"), marks))
    return out


def script(block: Block) -> str:
    """The block as a bash script: servers (``... &``) started through ``__serve``."""
    lines, n = [], 0
    logical = re.sub(r"\\\n", " ", block.text)  # continued lines, as bash reads them
    for ln in logical.splitlines():
        code = ln.split(" #", 1)[0].rstrip()
        if code.endswith("&") and not code.endswith("&&"):
            n += 1
            lines.append(f"__serve {n} {_quote(code[:-1].strip())}")
        else:
            lines.append(ln)
    return PRELUDE + "\n".join(lines) + "\n"


def _quote(text: str) -> str:
    return "'" + text.replace("'", "'\\''") + "'"


def scratch(folder: Path) -> Path:
    """A folder laid out like a fresh clone for the docs' commands: ``.venv``, ``src``,
    ``examples`` and the docs' scripts, with its own HOME and caches."""
    folder.mkdir(parents=True, exist_ok=True)
    for name in (".venv", "src"):
        (folder / name).symlink_to(ROOT / name)
    shutil.copytree(ROOT / "examples", folder / "examples")
    (folder / "docs").mkdir()
    for path in (ROOT / "docs").glob("*.py"):
        shutil.copy(path, folder / "docs" / path.name)
    (folder / "home").mkdir()
    return folder


def environment(folder: Path) -> dict[str, str]:
    """The blocks' environment: this checkout's ``softpad`` first on PATH, caches and HOME in
    the scratch folder, loopback-only ROS settings."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "PYTEST_"))}
    env.update(
        PATH=f"{ROOT / '.venv' / 'bin'}{os.pathsep}{env.get('PATH', '')}",
        PYTHONPATH=str(ROOT / "src"),
        MPLBACKEND="Agg",
        HOME=str(folder / "home"),
        XDG_CACHE_HOME=str(folder / "home" / ".cache"),
        ROS_IP="127.0.0.1",
        ROS_HOSTNAME="localhost",
        ROS_HOME=str(folder / "home" / ".ros"),
        ROS_MASTER_URI="http://127.0.0.1:11311",
    )
    return env


def _default_sigint() -> None:
    """In the child: SIGINT's default disposition (a shell started ignoring it, as a test run in
    the background starts, could not stop its servers with it)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _start_roscore(env: dict[str, str]) -> subprocess.Popen[bytes]:
    """A ROS 1 master on a free loopback port (ROS_MASTER_URI in ``env`` updated), ready."""
    from softpad.ros import rospy_available

    if shutil.which("roscore") is None or not rospy_available():
        pytest.skip("the block needs a roscore and rospy: ROS 1 not installed (make ros-deps)")
    port = _free_port()
    env["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    proc = subprocess.Popen(
        ["roscore", "-p", str(port)],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    # the system's Python, where Debian's rosgraph lives
    probe = [
        "/usr/bin/python3",
        "-c",
        "import rosgraph, sys; sys.exit(not rosgraph.is_master_online())",
    ]
    for _ in range(600):  # each probe waits on the master's socket; about 60 s in all
        if subprocess.run(probe, env=env, check=False, timeout=30).returncode == 0:
            return proc
        try:
            proc.wait(timeout=0.1)
            raise AssertionError("roscore exited before its master came up")
        except subprocess.TimeoutExpired:
            pass
    raise AssertionError("roscore's master did not come up within about 60 s")


def _server_lock() -> Any:
    """An exclusive lock held while a block serves: the docs' servers use fixed loopback
    ports (7447, 7450, 5757, 8786), so two such blocks (pytest-xdist workers) take turns."""
    import fcntl
    import tempfile

    f = open(Path(tempfile.gettempdir()) / "softpad-docs-servers.lock", "w")
    fcntl.flock(f, fcntl.LOCK_EX)
    return f


def run_block(block: Block, folder: Path, env: dict[str, str]) -> str:
    """Run a shell block in ``folder``; return its stdout and stderr. Fails the test, naming
    the page and line, when the block exits non-zero."""
    (folder / "block.sh").write_text(script(block))
    env = dict(env)
    roscore = _start_roscore(env) if "roscore" in block.marks else None
    lock = _server_lock() if "__serve" in script(block).replace(PRELUDE, "") else None
    try:
        proc = subprocess.run(
            ["bash", "block.sh"],
            preexec_fn=_default_sigint,
            cwd=folder,
            env=env,
            capture_output=True,
            text=True,
            timeout=TIMEOUT_S[block.slow],
            check=False,
        )
    finally:
        if lock is not None:
            lock.close()
        if roscore is not None:
            os.killpg(roscore.pid, 2)
            roscore.wait(timeout=30)
    output = proc.stdout + proc.stderr
    assert proc.returncode == 0, (
        f"{block.page}:{block.line}: the block exited {proc.returncode}\n{block.text}\n"
        f"--- stdout ---\n{proc.stdout[-4000:]}\n--- stderr ---\n{proc.stderr[-4000:]}"
    )
    assert "Traceback" not in output, f"{block.page}:{block.line}: a traceback\n{output[-4000:]}"
    return output


def check_output(expected: Block, output: str) -> None:
    """Every non-blank line of an ``output`` block appears in ``output`` (``...``: any text)."""
    for line in expected.text.splitlines():
        if not line.strip():
            continue
        pattern = ".*?".join(re.escape(part) for part in line.strip().split("..."))
        assert re.search(pattern, output), (
            f"{expected.page}:{expected.line}: the documented output line {line.strip()!r} "
            f"is not in what the block printed:\n{output[-3000:]}"
        )


def run_page(page: str, folder: Path, *, slow: bool, text: str | None = None) -> int:
    """Run a page's shell blocks in order in ``folder`` (the slow ones too when ``slow``) and
    check their documented output; return the number of blocks run."""
    env = environment(scratch(folder))
    ran, output, skipped = 0, None, []
    for block in blocks(page, text):
        if "output" in block.marks:
            if output is not None:  # None: the block before was not run now
                check_output(block, output)
            continue
        if not block.shell or block.not_run or (block.slow and not slow):
            output = None
            continue
        try:
            output = run_block(block, folder, env)
        except pytest.skip.Exception as exc:  # a ROS block without ROS: the others still run
            skipped.append(f"{page}:{block.line}: {exc.msg}")
            output = None
            continue
        ran += 1
    if skipped:
        pytest.skip(f"ran {ran} blocks of {page}; skipped " + "; ".join(skipped))
    return ran


def _pages_with(slow: bool) -> list[str]:
    return [
        p for p in PAGES if any(b.shell and not b.not_run and b.slow == slow for b in blocks(p))
    ]


@pytest.mark.parametrize("page", _pages_with(False))
def test_the_fast_blocks_of_a_page_run(page: str, tmp_path: Path) -> None:
    assert run_page(page, tmp_path, slow=False) >= 1


@pytest.mark.slow
@pytest.mark.parametrize("page", _pages_with(True))
def test_every_block_of_a_page_runs(page: str, tmp_path: Path) -> None:
    assert run_page(page, tmp_path, slow=True) >= 1


def test_no_block_looks_runnable_without_being_run() -> None:
    """An unlabelled fence that starts with a command is labelled bash (run) or text."""
    unlabelled = [
        f"{b.page}:{b.line}: {b.first_line}"
        for p in PAGES
        for b in blocks(p)
        if not b.lang and _LOOKS_RUNNABLE.match(b.first_line.lstrip("$ "))
    ]
    assert not unlabelled, "label these blocks bash (they run) or text:\n" + "\n".join(unlabelled)


def test_only_the_listed_blocks_are_not_run() -> None:
    counts = {p: sum(b.not_run for b in blocks(p)) for p in PAGES}
    assert {p: n for p, n in counts.items() if n} == NOT_RUN
    for b in (b for p in PAGES for b in blocks(p) if b.not_run):
        reason = next(m for m in b.marks if m.startswith("not run"))
        assert reason.split(":", 1)[-1].strip(), f"{b.page}:{b.line}: not run without a reason"


def test_every_output_block_follows_a_shell_block() -> None:
    for page in PAGES:
        previous = None
        for b in blocks(page):
            if "output" in b.marks:
                assert previous is not None and previous.shell, f"{page}:{b.line}"
            previous = b


BROKEN_PAGE = """# A page with a broken block

```bash
softpad plan --delta 0,0.124,0.078,0.109,0,0 > plan.txt
```

```bash
softpad plan --delta 0,0.124,0.078      # three values for a 2x3 pad: exit 2
```
"""

WRONG_OUTPUT = """# A page whose documented output is not what the command prints

```bash
softpad plan --delta 0,0.124,0.078,0.109,0,0
```

<!-- docs-test: output -->
```text
object 1: modules 1, 2
```
"""

CHAINED = """# A page whose second block reads the first block's file

```bash
softpad plan --delta 0,0.124,0.078,0.109,0,0 --json > plan.json
```

```bash
python -c "import json; print(sorted(json.load(open('plan.json'))))"
```

<!-- docs-test: output -->
```text
['objects', ...'schema_version']
```
"""


def test_a_broken_block_fails(tmp_path: Path) -> None:
    with pytest.raises(AssertionError, match=r"tmp.md:7: the block exited 2"):
        run_page("tmp.md", tmp_path / "broken", slow=False, text=BROKEN_PAGE)
    with pytest.raises(AssertionError, match="documented output line 'object 1: modules 1, 2'"):
        run_page("tmp.md", tmp_path / "wrong", slow=False, text=WRONG_OUTPUT)


def test_a_block_reads_what_an_earlier_block_of_its_page_wrote(tmp_path: Path) -> None:
    assert run_page("tmp.md", tmp_path, slow=False, text=CHAINED) == 2
