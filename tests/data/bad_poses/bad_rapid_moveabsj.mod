MODULE bad_rapid_moveabsj
  CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget p10 := [[100,0,500],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveAbsJ home, v1000, z50, tool0;
    MoveL p10, v200, fine, tool0;
  ENDPROC
ENDMODULE
