O3121 (G10 L14 P7 with 5100.2 = 1, .3 = 0, .4 = 0: the drill meets a hard stop at Z-5, goes back to R1, the G83 block ends there and the program goes on with #100 counting the overload: X30)
G98 G00 X0 Z10
#100=0
G10 L14 P7 Z100 R100
G83 X0 R1 Z-10 F300
G80
G00 X[20+#100*10]
M30
