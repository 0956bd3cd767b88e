"""Known testcases (ISPD-2018/2019 detailed-routing contests), the search path that finds them, and static regions."""

from xroute.testcases.known import (
    KNOWN_BY_NAME,
    KNOWN_TESTCASES,
    STATIC_REGIONS,
    KnownTestcase,
    StaticRegion,
    known_testcase,
)
from xroute.testcases.registry import DEMO, EMBEDDED_ROOT, ENV_VAR, FoundTestcase, find_testcase, locate_all, search_path

__all__ = [
    "DEMO",
    "EMBEDDED_ROOT",
    "ENV_VAR",
    "KNOWN_BY_NAME",
    "KNOWN_TESTCASES",
    "STATIC_REGIONS",
    "FoundTestcase",
    "KnownTestcase",
    "StaticRegion",
    "find_testcase",
    "known_testcase",
    "locate_all",
    "search_path",
]
