O3200 (inclined-axis control: the spec's worked table, L4701-4765, with X inclined at -30 degrees)
G98 G53 X0 Z0
G53 X-100 Z-50
G00 X10 Z0
G00 X-10 Z5
G01 X20 Z-10 F1000
G00 Z[#5002+5]
G53 X0 Z0
M30
