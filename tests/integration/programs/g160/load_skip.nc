O3198 (G31 P98: the tailstock B1 finds the centre at B-150 at the load ratio G10 L14 P6 sets)
G98 G00 X20 Z0
G00 B-140
G10 L14 P6 B50
G31 B-200 F300 P98 R100
#101=#5063
G00 X[20+#100*10]
G00 B[#101+10]
M30
