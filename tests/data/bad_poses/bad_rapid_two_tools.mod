MODULE bad_rapid_two_tools
  PERS tooldata gun := [TRUE, [[0, 0, 120], [1, 0, 0, 0]], [1, [0, 0, 1], [1, 0, 0, 0], 0, 0, 0]];
  CONST robtarget p10 := [[100,0,500],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveL p10, v100, fine, tool0;
    MoveL [[10,20,30],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, gun;
  ENDPROC
ENDMODULE
