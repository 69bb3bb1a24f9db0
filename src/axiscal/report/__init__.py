"""Plots and reports: matplotlib figures and self-contained HTML pages."""
