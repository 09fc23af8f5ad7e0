MODULE bad_rapid_undeclared
  CONST robtarget p10 := [[100,0,500],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveJ p10, v1000, z50, tool0;
    MoveC p20, p30, v200, fine, tool0;
  ENDPROC
ENDMODULE
