(gsk D3-11: G20 is not in the table of B.1: alarm)
G20
M30
