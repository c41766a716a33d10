# rift_embed_text(<file> <delimiter> <out_var>): the file's text as a list of C++ raw string literals
# (`R"<delimiter>(...)<delimiter>",` one per line of the result), for a configure_file template to
# paste into an array. Each literal holds at most about 8 KB, cut after a line end so that no UTF-8
# character is split, and stays far below any compiler's limit on one literal. A text that holds the
# closing sequence `)<delimiter>"` is refused: it would end its literal early.
function(rift_embed_text file delimiter out_var)
  file(READ "${file}" text)
  string(FIND "${text}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} holds ')${delimiter}\"', which would end its raw string literal early")
  endif()
  set(literals "")
  string(LENGTH "${text}" left)
  while(left GREATER 0)
    string(SUBSTRING "${text}" 0 8192 head)
    string(LENGTH "${head}" taken)
    if(taken LESS left)
      string(FIND "${head}" "\n" last_newline REVERSE)
      if(last_newline GREATER -1)
        math(EXPR taken "${last_newline} + 1")
        string(SUBSTRING "${text}" 0 ${taken} head)
      endif()
    endif()
    string(APPEND literals "    R\"${delimiter}(${head})${delimiter}\",\n")
    string(SUBSTRING "${text}" ${taken} -1 text)
    string(LENGTH "${text}" left)
  endwhile()
  set(${out_var} "${literals}" PARENT_SCOPE)
endfunction()
