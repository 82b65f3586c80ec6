"""Records of runs: every frame, event and plan, saved/loaded, plotted like Fig. 6.8.

:class:`RunLog` is the recorder hook of :class:`softpad.control.GraspExecution`.
"""

from softpad.record._log import LOG_FORMAT, RunLog

__all__ = ["LOG_FORMAT", "RunLog"]
