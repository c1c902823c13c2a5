"""Task generation at scale: new, proven scenarios from our hand-written ones (`manage.py
generate`, the admin's "Generate variants…"). One job per module: templates (families),
arrivals (timing), phrasing, compose (one candidate), proofs, generate (the run, the files, the
manifest), figures (diversity), variants and admin (the admin's page)."""
