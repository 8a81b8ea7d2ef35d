0
(header comment)
%
O0120 (NAME OF PROGRAM)
G00 X1 (move) Z2 ; trailing
G01 X2 F100 // slash comment
(only a comment)

;
N30 G00 X3 (unclosed
M30
%
