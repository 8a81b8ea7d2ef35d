O1000 (spec L4850-4866: G10 L14 P1 watches Z's load in G01 at 80 %, then X's with J2 in place of Z's, then cancels every check)
G10 P1 L14 Z80
G00 X0 Z0
G01 W-10 F20
G00 Z0
G10 P1 L14 X80 J2
G01 U-10 F20
G00 X0 Z0
G10 P1 L14
M30
