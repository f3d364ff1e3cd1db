"""Engineering goals the bench measures (writing speed, batch throughput, big scenes),
kept apart from the papers' reproductions."""
