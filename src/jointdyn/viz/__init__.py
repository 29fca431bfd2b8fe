"""Figures: static plots, interactive pages, animations and the reproduction's figure set."""
