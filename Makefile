# SoftPad: `make demo` runs the main job on the simulated box, `make test` runs the checks
# (all but those marked slow: target 3 minutes on 2 cores), `make test-slow` the slow ones
# (full trials, FEM solves, the demo's report); CI (.ci/run) runs both.
# Both create the virtual environment in .venv and install everything on first use.
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin

.PHONY: demo test test-slow bench lint typecheck venv clean ros-deps ros2-interfaces results ext

$(VENV)/.installed: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[dev]'
	touch $@

venv: $(VENV)/.installed

# The compiled over-pressure guard (src/softpad/box/_fastguard.c, setup.py), built in place:
# `pip install -e .` builds it too; this is for an environment installed before it existed.
# Without a C compiler the daemon runs its guard in Python only (and says so).
PYINFO = $(BIN)/python -c "import sysconfig as s; print(s.get_config_var('$(1)') or s.get_paths()['include'])"
ext: venv
	@if command -v cc >/dev/null; then \
	    cc -O2 -std=c11 -Wall -shared -fPIC -I"$$($(call PYINFO,INCLUDEPY))" src/softpad/box/_fastguard.c \
	        -o "src/softpad/box/_fastguard$$($(call PYINFO,EXT_SUFFIX))" -lpthread; \
	    cc -O2 -std=c11 -Wall -ffp-contract=off -shared -fPIC -I"$$($(call PYINFO,INCLUDEPY))" \
	        src/softpad/box/_fastsim.c -o "src/softpad/box/_fastsim$$($(call PYINFO,EXT_SUFFIX))"; \
	    cc -O2 -std=c11 -Wall -ffp-contract=off -shared -fPIC -I"$$($(call PYINFO,INCLUDEPY))" \
	        src/softpad/control/_fastmonitor.c -o "src/softpad/control/_fastmonitor$$($(call PYINFO,EXT_SUFFIX))"; \
	    mj="$$($(BIN)/python -c 'import mujoco, os; print(os.path.dirname(mujoco.__file__))' 2>/dev/null)"; \
	    if [ -n "$$mj" ]; then cc -O2 -std=c11 -Wall -ffp-contract=off -shared -fPIC \
	        -I"$$($(call PYINFO,INCLUDEPY))" -I"$$mj/include" src/softpad/sim/_fastworld.c \
	        -o "src/softpad/sim/_fastworld$$($(call PYINFO,EXT_SUFFIX))"; \
	    else echo "ext: no mujoco: the compiled world steps are not built"; fi; \
	else echo "ext: no C compiler: the compiled guard, solve, monitor rates and world steps are not built (their tests are skipped)"; fi

# PYTHONDONTWRITEBYTECODE cleared as for the tests (below): the demo's processes (the command,
# its trial workers, the reference plans' process) compile the sources once, not each time.
demo: ext
	MPLBACKEND=Agg PYTHONDONTWRITEBYTECODE= $(BIN)/softpad demo --out report --force

lint: venv
	$(BIN)/ruff check src tests examples
	$(BIN)/ruff format --check src tests examples

typecheck: venv
	$(BIN)/mypy

# Debian's ROS 1 packages for the ROS node and its tests (docs/ros.md); installed only when missing,
# and only as root (elsewhere the ROS tests are skipped with the reason).
# python3-rosbag reads the ROS 1 bags of 'softpad log export --rosbag1' back in a test;
# python3-actionlib serves the grasp action; check_urdf (liburdfdom-tools) reads the pad's URDF.
ROS_APT := ros-core python3-rospy python3-std-msgs python3-geometry-msgs python3-sensor-msgs \
	python3-diagnostic-msgs python3-std-srvs python3-tf2-msgs python3-rostopic python3-rosbag \
	python3-actionlib python3-actionlib-msgs liburdfdom-tools
ros-deps:
	@if command -v roscore >/dev/null && [ -f /usr/lib/python3/dist-packages/rospy/__init__.py ] \
	    && [ -d /usr/lib/python3/dist-packages/tf2_msgs ] \
	    && [ -d /usr/lib/python3/dist-packages/actionlib ] && command -v check_urdf >/dev/null \
	    && [ -f /usr/lib/python3/dist-packages/rosbag/__init__.py ]; then :; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "ros-deps: running as root: installing Debian's ROS 1 packages with apt-get: $(ROS_APT)"; \
	    (apt-cache policy ros-core | grep -q 'Candidate: [0-9]' || apt-get update -q) && \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $(ROS_APT); \
	else echo "ros-deps: ROS 1 not installed and not root: ROS tests will be skipped"; fi

# ROS 2 (rclpy wheels, in .venv through the dev extra): tf2_msgs and softpad_msgs have no wheel;
# built once into .venv with the wheels' rosidl generators (CMake, g++; about 1 min; docs/ros.md).
# strace: a test checks that every datagram of the ROS 2 node goes to 127.0.0.1.
ros2-interfaces: venv
	@if ! command -v cmake >/dev/null || ! command -v g++ >/dev/null \
	    || ! command -v strace >/dev/null; then \
	    if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	        (apt-cache policy cmake | grep -q 'Candidate: [0-9]' || apt-get update -q) && \
	        DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
	            cmake g++ strace python3-dev; \
	    fi; fi
	@$(BIN)/python -c "import softpad_msgs.action, tf2_msgs.msg" 2>/dev/null \
	    || $(BIN)/softpad ros2 build-interfaces \
	    || echo "ros2-interfaces: not built: ROS 2 tests will be skipped with the reason"

# `--cpu-durations N` lists the N tests that used the most CPU (tests/conftest.py). Not
# `--dist loadgroup`: with pytest 9 and pytest-xdist 3.8 it groups nothing (xdist renames the
# nodeid through an attribute pytest 9 no longer reads); work shared by tests is shared inside one.
# `--dist worksteal`: a worker that runs out of tests takes half of the other's queue, so the
# two finish together although a few tests take seconds (issue 50). PYTHONDONTWRITEBYTECODE
# cleared: where the environment sets it, every worker and every command a test starts compiled
# (and pytest re-wrote) the sources anew: collection 6.9 -> 3.2 CPU s, `softpad run` 0.9 ->
# 0.7 CPU s (the __pycache__ folders are git-ignored).
# TEST_WORKERS: `make test` runs 3 workers on the 2 cores: about a third of its wall time on
# a quiet machine was cores idle while tests waited on the processes they start (ROS 1 masters
# and nodes paced at real time, docs servers, link timeouts: 279 s wall for 360 CPU s); a
# third worker computes while one waits (issue 50). `make test TEST_WORKERS=2` as before.
# tests/conftest.py deals the heaviest files first, one per worker.
TEST_ENV := MPLBACKEND=Agg PYTHONDONTWRITEBYTECODE=
TEST_WORKERS ?= 3
test: lint typecheck ros-deps ros2-interfaces ext
	$(TEST_ENV) $(BIN)/pytest -n $(TEST_WORKERS) --dist worksteal -q -m "not slow" --durations=10

test-slow: venv ros-deps ros2-interfaces ext
	$(TEST_ENV) $(BIN)/pytest -n 2 --dist worksteal -q -m slow --durations=10

bench: ext
	MPLBACKEND=Agg $(BIN)/softpad bench

# Every result the docs quote, rerun at this commit into docs/results.md (about 30 min on 2
# cores: seeds 0-1 for the trials; `softpad results --full --force` for the docs' seeds).
results: ext
	MPLBACKEND=Agg $(BIN)/softpad results --force

clean:
	rm -rf $(VENV) build src/*.egg-info .pytest_cache .mypy_cache .ruff_cache report
