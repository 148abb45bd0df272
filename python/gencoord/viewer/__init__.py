"""The browser viewer: a trajectory as one self-contained HTML page, and headless Chromium."""
