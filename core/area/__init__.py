"""Area-based (intensity/frequency-domain) matching."""
