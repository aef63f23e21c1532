"""reportgen: config-driven simulator and report generator for classical mechanics."""

__version__ = "0.2.0"
