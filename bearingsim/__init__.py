"""bearingsim: a Modelica-style, equation-based simulator for rolling-bearing systems."""

__version__ = "0.1.0"
