"""Known testcases (ISPD-2018/2019 detailed-routing contests), the search path that finds them, and static regions."""

from testcases.registry import (
    KNOWN_TESTCASES,
    STATIC_REGIONS,
    FoundTestcase,
    KnownTestcase,
    StaticRegion,
    find_testcase,
    search_path,
)

__all__ = [
    "KNOWN_TESTCASES",
    "STATIC_REGIONS",
    "FoundTestcase",
    "KnownTestcase",
    "StaticRegion",
    "find_testcase",
    "search_path",
]
