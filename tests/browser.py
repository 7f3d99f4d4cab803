"""Open a page in headless Chromium for the tests that check what a designer sees in a browser.

The tests skip with a clear message where no Chromium is installed (`.ci/run` installs Debian's
``chromium`` package). The page is loaded from a ``file://`` address with the network switched off,
so a page that needs the network shows it as missing content.
"""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from matplotlib import image

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "chrome")
FLAGS = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--hide-scrollbars",
    "--no-first-run",
    "--proxy-server=127.0.0.1:9",
    "--proxy-bypass-list=<-loopback>",
)


@dataclass(frozen=True)
class Rendered:
    """A page as Chromium shows it: the screenshot's pixels (rows x columns x RGB(A), 0..1) and the
    document after its scripts ran."""

    pixels: np.ndarray
    dom: str

    def is_blank(self, tolerance: float = 0.02) -> bool:
        """Whether the screenshot is one flat colour (nothing drawn)."""
        rgb = self.pixels[..., :3]
        return bool(np.ptp(rgb.reshape(-1, 3), axis=0).max() <= tolerance)


def chromium() -> str:
    """The path of a Chromium executable, or skip the calling test saying why."""
    for name in CANDIDATES:
        found = shutil.which(name)
        if found:
            return found
    pytest.skip("no headless Chromium found (install Debian's `chromium` package; .ci/run does)")


def render(page: Path, width: int = 1280, height: int = 2000, timeout: float = 120) -> Rendered:
    """Load ``page`` in headless Chromium; return its screenshot and its document after scripts."""
    executable = chromium()
    url = Path(page).resolve().as_uri()
    shot = Path(page).resolve().parent / ".screenshot.png"
    base = [executable, *FLAGS, f"--window-size={width},{height}"]
    try:
        subprocess.run([*base, f"--screenshot={shot}", url], check=True, capture_output=True, timeout=timeout)
        dom = subprocess.run([*base, "--dump-dom", url], check=True, capture_output=True, timeout=timeout)
        pixels = image.imread(shot)
    finally:
        shot.unlink(missing_ok=True)
    return Rendered(pixels=pixels, dom=dom.stdout.decode("utf-8", "replace"))
