O3110 (G10 L14 P1: the tailstock B1's load watched in G01 at 80 %; pressed against the centre at B-150 it overloads: alarm 1280 at line 6, and nothing moves after)
G98 G00 X20 Z0
G00 B-149
G10 L14 P1 B80
G01 B-149.5 F300
G01 B-151 F300
G00 X40
M30
