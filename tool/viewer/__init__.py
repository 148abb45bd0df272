"""Headless Chromium for the viewer page's browser tests, benchmark and screenshots."""
