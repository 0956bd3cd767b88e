"""Fuzz target for the YAML configs (`route --config`, `batch`): any bytes as a config file.

    python fuzz/fuzz_yaml.py [libFuzzer flags] [CORPUS_DIR ...]     (with atheris: pip install atheris)
    python fuzz/fuzz_yaml.py --plain SECONDS [SEED_FILE ...]        (no atheris: a built-in mutator;
                                                                     XROUTE_FUZZ_SEED=N picks its seed)

Each input is written to a file and loaded twice, as an xroute config
(:func:`xroute.config.load_config`) and as a batch file
(:func:`xroute.cli.batch_config.load_batch_config`). Loading must return a config or raise
:class:`xroute.config_schema.ConfigError` with a line inside the file; anything else
(RecursionError, TypeError, a ConstructorError, ...) is a crash, and so is a config that loads
with a number that is not finite (NaN, infinity) or a setting read from a YAML 1.1 base-60
number (``1:30``). Under atheris the target is
coverage-guided (libFuzzer flags such as -max_total_time=600 -dict=... apply); fuzz/fuzz.sh runs it
beside the C++ targets. Inputs that crashed are kept as tests/fuzz_regressions/yaml/<name>.yaml
(tests/test_hostile_input.py loads every file there).
"""

from __future__ import annotations

import os
import random
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

_DIR = Path(tempfile.mkdtemp(prefix="xroute-fuzz-yaml-"))
_FILE = _DIR / "fuzz.yaml"


def _import_targets():
    from xroute.cli.batch_config import load_batch_config
    from xroute.config import load_config
    from xroute.config_schema import ConfigError

    return load_config, load_batch_config, ConfigError


def check_numbers(value: object, where: str = "config") -> None:
    """Raises AssertionError for a number in a loaded config that is not finite."""
    import dataclasses
    import math

    if isinstance(value, float) and not math.isfinite(value):
        raise AssertionError(f"{where} = {value!r}: a loaded config holds a number that is not finite")
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            check_numbers(getattr(value, f.name), f"{where}.{f.name}")
    elif isinstance(value, (tuple, list)):
        for i, v in enumerate(value):
            check_numbers(v, f"{where}[{i}]")


def one_input(data: bytes, targets=None) -> None:
    """Loads ``data`` as both kinds of config; raises on anything but a config or a ConfigError."""
    load_config, load_batch_config, ConfigError = targets or _import_targets()
    _FILE.write_bytes(data)
    # Line breaks as YAML counts them (\r, \r\n, \x85, \u2028 too): str.splitlines is a superset.
    lines = len(data.decode("utf-8", "replace").splitlines()) + 1
    for load in (load_config, load_batch_config):
        try:
            check_numbers(load(_FILE))
        except ConfigError as exc:
            if not (exc.path == str(_FILE) and 0 <= exc.line <= lines):
                raise AssertionError(f"ConfigError names {exc.path}:{exc.line} (the file has {lines} lines)") from exc
            if "\n" in str(exc):
                raise AssertionError(f"ConfigError message is not one line: {exc!r}") from exc


SEED_TEXTS = [
    b"region: {region_size: 3}\nrouter: {iteration_count: 2, thread_count: 1}\n",
    b"testcases: [demo]\npolicies: [heuristic, random]\nsettings:\n  - {name: a, region_size: 3}\n",
    b"base: &b {region_size: 3}\nregion:\n  <<: *b\n",
    b"router:\n  iteration_schedule:\n    - {region_size: 5, offset: 0}\n    - {region_size: 5, offset: 2}\n",
    b"policy: !!python/name:os.system\n",
    b"policy: {call_timeout: .nan, seed: 1:30}\ncost: {via_weight: .inf, drv_weight: -.inf}\n",
    b"testcases: [demo]\ngates: {max_wirelength_increase_pct: .NaN}\n",
]
TOKENS = [b"<<: ", b"&a ", b"*a", b"!!python/name:os.system", b"!custom ", b"!!binary ", b"[", b"]", b"{", b"}",
          b": ", b"- ", b"\n  ", b"---\n", b"2147483648", b"99999999999999999999", b"-1", b".inf", b".nan",
          b"2020-13-45", b"~", b"null", b"region_size", b"iteration_schedule", b"offset", b"policy", b"seed",
          b"testcases", b"settings", b"name", b"gates", b"baseline", b"\xff", b"\t", b"'", b'"', b"?", b"|", b">",
          b"1:30", b"-2:05:00", b"1:30.5", b"!!int ", b"!!float ", b".NaN", b"-.inf", b".Inf", b"0x7fffffffffffffff",
          b"1_0", b"0o17", b"017", b"1e400", b"call_timeout: ", b"via_weight: ", b"drv_weight: ",
          b"max_vias_increase_pct: "]


def plain_fuzz(seconds: float, seeds: list[bytes]) -> int:
    """A simple mutation loop (no coverage feedback) for machines without atheris."""
    targets = _import_targets()
    rng = random.Random(int(os.environ.get("XROUTE_FUZZ_SEED", "1")))
    corpus = list(seeds) or list(SEED_TEXTS)
    deadline = time.monotonic() + seconds
    runs = 0
    while time.monotonic() < deadline:
        data = bytearray(rng.choice(corpus))
        for _ in range(rng.randint(1, 6)):
            op = rng.random()
            i = rng.randrange(len(data) + 1)
            if op < 0.4:
                data[i:i] = rng.choice(TOKENS)
            elif op < 0.6 and data:
                del data[i:i + rng.randint(1, 8)]
            elif op < 0.8 and data:
                data[min(i, len(data) - 1)] = rng.randrange(256)
            else:
                other = rng.choice(corpus)
                j = rng.randrange(len(other) + 1)
                data[i:i] = other[j:j + rng.randint(1, 40)]
        if rng.random() < 0.02:
            depth = rng.randint(50, 6000)
            data = b"a: " + b"[" * depth + b"]" * depth
        try:
            one_input(bytes(data), targets)
        except Exception as exc:  # noqa: BLE001 - a finding
            crash = REPO / "build" / "fuzz" / "artifacts" / f"yaml-crash-{runs}.yaml"
            crash.parent.mkdir(parents=True, exist_ok=True)
            crash.write_bytes(bytes(data))
            print(f"CRASH after {runs} runs: {type(exc).__name__}: {exc} -> {crash}")
            return 1
        runs += 1
        if rng.random() < 0.05 and len(corpus) < 500:
            corpus.append(bytes(data))
    print(f"stat::number_of_executed_units: {runs}")
    print(f"stat::average_exec_per_sec: {int(runs / max(seconds, 1e-9))}")
    print(f"Done {runs} runs in {int(seconds)} second(s)")
    return 0


def main() -> int:
    if len(sys.argv) >= 3 and sys.argv[1] == "--plain":
        seeds = [Path(p).read_bytes() for p in sys.argv[3:] if Path(p).is_file()]
        return plain_fuzz(float(sys.argv[2]), seeds)
    import atheris

    with atheris.instrument_imports():
        import yaml  # noqa: F401

        import xroute.cli.batch_config  # noqa: F401
        import xroute.config  # noqa: F401
        import xroute.config_schema  # noqa: F401
        import xroute.safe_yaml  # noqa: F401
    targets = _import_targets()
    atheris.Setup(sys.argv, lambda data: one_input(data, targets))
    atheris.Fuzz()
    return 0


if __name__ == "__main__":
    os.environ.setdefault("XROUTE_TESTCASES", str(REPO.parent / "shared" / "testcases"))
    sys.exit(main())
