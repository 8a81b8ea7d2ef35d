O3105 (spec L5246-5249: G10 L14 P6 sets the load ratios G31 P98 skips at; without it param 5511; without the runtime the skip comes at the end point)
G98 G00 X40 Z10
G31 W-20 F100 P98 R100
G10 L14 P6 Z35
G31 U-4 W-5 F100 P98
G01 X[#5061+#100*2] F500
G10 L14 P6
M30
