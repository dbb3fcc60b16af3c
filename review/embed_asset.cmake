# cmake -DINPUT=file -DOUTPUT=file.cc -DNAME=kName -P embed_asset.cmake
# Writes OUTPUT defining `const char* const birotor::NAME` = INPUT's bytes, as
# raw string literals of at most 8000 characters each (compilers' limits).
file(READ ${INPUT} content)
string(LENGTH "${content}" length)
set(out "// Generated from ${INPUT} by review/embed_asset.cmake; do not edit.\nnamespace birotor {\nextern const char* const ${NAME};\nconst char* const ${NAME} =\n")
set(at 0)
while(at LESS length)
  string(SUBSTRING "${content}" ${at} 8000 chunk)
  string(APPEND out "R\"birotor_asset(${chunk})birotor_asset\"\n")
  math(EXPR at "${at} + 8000")
endwhile()
string(APPEND out ";\n}  // namespace birotor\n")
file(WRITE ${OUTPUT} "${out}")
