"""Figure functions: arrays in, matplotlib Figure out (Agg backend only).

Every function takes ``ax=None`` (a new figure is made only when needed) and
keeps styling arguments keyword-only.
"""
