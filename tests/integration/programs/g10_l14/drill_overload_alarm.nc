O3120 (G10 L14 P7, spec L4965-4993: Z1's load watched at 100 % in the G83's feed; the drill meets a hard stop at Z-5, goes back to R1 at once, then alarm 1282 at line 4; X50 never drills)
G98 G00 X0 Z10
G10 L14 P7 Z100
G83 X0 R1 Z-10 F300
X50
G80
G10 L14 P7
M30
