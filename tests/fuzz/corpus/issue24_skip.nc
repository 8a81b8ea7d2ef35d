0
%
O0001 (issue 24: G31 skip on its inputs, the skip position and the refused P forms)
G98 G00 X20 Z0
G31 W-50 F300 L13 R100
#101=#5062
G31 U10 K13
G31 W5 I-7
G31 W-5 P98
M30
%
