MODULE bad_rapid_nonunit
  CONST robtarget p10 := [[100,0,500],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget p20 := [[200,0,500],[0.9,0,0.1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveJ p10, v1000, z50, tool0;
    MoveL p20, v200, fine, tool0;
  ENDPROC
ENDMODULE
