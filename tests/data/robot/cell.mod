MODULE cell
  PERS tooldata gun := [TRUE, [[0, 0, 120], [1, 0, 0, 0]], [1, [0, 0, 1], [1, 0, 0, 0], 0, 0, 0]];
  PERS wobjdata table := [FALSE, TRUE, "", [[500, -200, 100], [0.7071067811865476, 0, 0, 0.7071067811865476]], [[0, 0, 50], [1, 0, 0, 0]]];
  CONST robtarget p10 := [[10, 20, 30], [0, 1, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[300, 0, 40], [0, 0.7071067811865476, 0.7071067811865476, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PROC main()
    ConfL \Off;
    MoveJ p10, v1000, z50, gun \WObj:=table;
    MoveL p20, v200, fine, gun \WObj:=table;
    MoveL [[100, 100, 40], [0, 1, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v200, fine, tool0 \WObj:=table;
  ENDPROC
ENDMODULE
