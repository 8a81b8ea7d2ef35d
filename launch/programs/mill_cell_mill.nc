O2601 (mill cell, the three-axis mill CH2: a contour under G41 D1 and G43 H1, then holes by G81 and G83)
#11001 = 100. (H1 geometry: the tool is 100 mm long)
#13001 = 5. (D1 geometry: a cutter of radius 5)
G17 G90 G40 G49 G80
M03 S3000
G00 X-20. Y-20.
G43 Z10. H1
G01 Z-3. F600
G41 G01 X0 Y0 D1 F1800
Y40.
X30.
G02 X40. Y30. R10.
G01 Y0
X0
G40 G01 X-20. Y-20.
G00 Z10.
G99 G81 X10. Y10. Z-5. R2. F600
X30.
G98 G83 X20. Y20. Z-12. R2. Q4. F600
G80
G00 Z50.
G49
M05
G04.1 P1 Q12 (the lathe has finished too)
M30
