%
O0004
(Seed 004, Fig. 10: the G-code of the test part, printed as one run-on paragraph.)
(One block a line as shared/SEEDS-SPEC.md 4.2.5 reconstructs it, L1-L76.)
(Repairs:)
(L40: the printed tab between X70. and Y100. is a layout artefact: two blocks.)
(L74: the listing omits layers 2-6 of the finishing before this arc; from where layer 1 ends,)
(X70 Y101 Z0, its I1 J0 gives radii 1 and 16. The block marked REPAIR puts the tool)
(at X54 Y100 Z-30, where layer 6 reaches that corner, so the arc is the printed R1 corner.)
(Kept as printed: L54 Z-2. though 5 mm a layer is announced; the omitted layers 2-5 of the roughing.)
G54 G90 G21 G40 G49 M5 M9
G0 Z100. (Move to the secure plane)
(To drill and ream a thru hole)
T2 M6 (Use a spiral drill, diameter 20mm)
G43 H2 (Length compensation by 70mm)
M8 M3 F900. S720
G0 Z30.
G90 G99 G81 X20. Y60. Z-18. R10.
G99 G81 X20. Y60. Z-36. R10. F1800.
G99 G81 X20. Y60. Z-60. R10. F1350.
G1 Z10. F1800.
G80 G49 M5 M9 (end of drilling cycle)
T3 M6 (Use a reamer, diameter 22mm)
G43 H3 (Length compensation by 50mm)
M8 M3 S1080
G90 G99 G85 X20. Y60. Z-60. R10.
G80 G49 M5 M9 (End of reaming cycle)
(To cut a pocket, rough & finish)
T1 M6 (Use an endmill, diameter 18mm)
G43 H1 (Length compensation by 50mm)
M8 S1200 M3 F2400.
G0 Z30.
X64.754 Y50.069 Z15.
(To rough pocket in 5 layers, 5.9/layer)
(First 2 blocks: to run helical approach)
G2 X77.2 Y55. Z-5.9 I5.246 J4.932
G2 X70. Y55. I-3.60 J0.
G1 Y90.
X75.
Y50.
X65.
Y90.
X70.
Y95.
X80.
Y45.
X60.
Y95.
X70.
Y100.
X85.
Y40.
X55.
Y100.
X70.
Z0.
G0 X69.532 Y47.815 (End of 1st layer)
(Code of next 4 layers omitted)
(To finish pocket in 6 layers. 5mm/layer)
(Bottom allowance 0.5, side allowance 1)
G0 Z30.
X74.890 Y60.285 Z15.
(First 2 blocks: to run helical approach)
G2 X77.2 Y55. Z-2. I-4.891 J-5.285
G2 X70. Y55. I-3.60 J0.
G1 Y93.
X78.
Y47.
X62.
Y93.
X70.
Y101.
X85.
G2 X86. Y100. I0. J-1.
G1 Y40.
G2 X85. Y39. I-1. J0.
G1 X55.
G2 X54. Y40. I0. J1.
G1 Y100.
G2 X55. Y101. I1. J0.
G1 X70.
Z0. (End of 1st layer)
(Code of rest of layers omitted)
G1 X54. Y100. Z-30. (REPAIR: stands for the omitted layers 2-6)
G2 X55. Y101. I1. J0. (now Z-30.)
G1 X70. Z15. (End of finishing)
M30
%
