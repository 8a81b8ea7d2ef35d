O3111 (G10 L14 P4/P5 and P41/P51: the tailstock B1 fed into the centre at B-150 by G31 P98, skipping at 50 %; timer 4 counts its load above 20 %, timer 5 above 900 % never; #100 gets B's bit, 4, and #101 stays 0: X goes to 60)
G98 G00 X20 Z0
G00 B-149
G10 L14 P6 B50
G10 L14 P4 B20
G10 L14 P5 B900
G31 B-151 F300 P98
G00 B-149
#100=0
G10 P41 L14 B0 R100
#101=0
G10 P51 L14 B0 R101
G00 X[20+#100*10+#101*100]
M30
