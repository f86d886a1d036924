"""Write .ci/constraints.txt: the installed version of every package the app and its tests need (the dependency
closure of mechanism-dynamics-lab[test,postgres,bench]), after a full run of the suite has passed with them.

    python3 .ci/constraints.py      # from the checkout, in the environment the suite passed in
"""
from __future__ import annotations

import re
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

from packaging.requirements import Requirement

HEADER = ("# The versions the whole suite passed with (tests/run.sh installs with them); pyproject.toml keeps the "
          "lower bounds.\n# Regenerate after an upgrade the suite passes with: python3 .ci/constraints.py\n")


def closure(name: str, extras: set[str]) -> dict[str, str]:
    seen: dict[str, tuple[str, set[str]]] = {}
    stack = [(name, extras)]
    while stack:
        package, wanted = stack.pop()
        try:
            dist = distribution(package)
        except PackageNotFoundError:
            continue
        key = re.sub(r"[-_.]+", "-", dist.metadata["Name"]).lower()
        if key in seen and wanted <= seen[key][1]:
            continue
        seen[key] = (dist.version, seen.get(key, ("", set()))[1] | wanted)
        for text in dist.requires or []:
            requirement = Requirement(text)
            if requirement.marker is None or any(requirement.marker.evaluate({"extra": e}) for e in wanted | {""}):
                stack.append((requirement.name, set(requirement.extras)))
    return {key: version for key, (version, _) in seen.items() if key != name}


if __name__ == "__main__":
    pins = closure("mechanism-dynamics-lab", {"test", "postgres", "bench"})
    target = Path(__file__).with_name("constraints.txt")
    target.write_text(HEADER + "".join(f"{key}=={pins[key]}\n" for key in sorted(pins)), encoding="utf-8")
    print(f"{len(pins)} packages pinned in {target}")
