"""reportgen: config-driven simulator and report generator for classical mechanics."""

__version__ = "0.1.0"
