O1000 (gsk A.6.4 rule 2: three points on one line)
G00 X0 Z0
G05 X20 Z-10 I5 K-5 F30
M30
