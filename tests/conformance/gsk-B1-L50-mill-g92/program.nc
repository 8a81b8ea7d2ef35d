(gsk B.1 L50: G92 makes the current position read the given values; nothing moves)
G90 G00 X10 Y10 Z10
G92 X0 Y0 Z0
IF [#5041 NE 0] #3000=1 (G92: X READS 0)
G00 X5 Y5
G91 X5 Z-2
M30
