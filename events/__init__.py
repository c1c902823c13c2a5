"""The core: every run is an append-only event log; state is the fold of that log.

This package knows nothing about any particular environment (email, stocks, …). Environments
register themselves with `events.registry`.
"""
