# Build steps of the kernel's GLSL (shaders/CMakeLists.txt), run as
#   cmake -DMODE=<emit|embed> ... -P EmbedGlsl.cmake
#
# emit:  PRELUDE, BODIES (files joined by '|'), CHECK_MAIN, OUTPUT, CHECK_OUTPUT.
#        OUTPUT = the prelude, then each body behind a `#line 1 <n>` (compiler
#        messages in source string n point into the n-th body), then an
#        #undef of every public name the prelude renamed (`#define covers
#        bc_covers`: the shader after the library sees only bc_covers), then a
#        #line that hands the rest of the shader back to source string 0 with
#        the numbering of the whole text. CHECK_OUTPUT = OUTPUT + CHECK_MAIN.
# embed: INPUT, OUTPUT (.cpp): INPUT's bytes as a C++ array behind
#        blurcull::glsl::kernel_source() (shaders/include/blurcull/glsl/kernel_glsl.hpp).
cmake_minimum_required(VERSION 3.16)

function(blurcull_count_lines text out)
  string(REGEX MATCHALL "\n" newlines "${text}")
  list(LENGTH newlines count)
  set(${out} ${count} PARENT_SCOPE)
endfunction()

# The names the prelude renames with `#define <name> bc_<name>`.
function(blurcull_public_names text out)
  string(REGEX MATCHALL "\n#define[ \t]+[A-Za-z_][A-Za-z_0-9]*[ \t]+bc_[A-Za-z_0-9]*" lines "${text}")
  set(names "")
  foreach(line ${lines})
    string(REGEX REPLACE "^\n#define[ \t]+([A-Za-z_][A-Za-z_0-9]*)[ \t]+bc_([A-Za-z_0-9]*)$" "\\1;\\2" parts "${line}")
    list(GET parts 0 name)
    list(GET parts 1 suffix)
    if(name STREQUAL suffix)
      list(APPEND names ${name})
    endif()
  endforeach()
  set(${out} ${names} PARENT_SCOPE)
endfunction()

function(blurcull_read_text path out)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "EmbedGlsl: ${path} does not exist")
  endif()
  file(READ "${path}" text)
  if(NOT text MATCHES "\n$")
    string(APPEND text "\n")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# Every intermediate of the shared text `precise` (docs/glsl.md, "The GPU
# arithmetic model"): GLSL may fuse a*b+c or reassociate any expression whose
# value does not reach a `precise` l-value. The bodies are rewritten line by
# line (comments and preprocessor lines untouched):
#  - every declaration of a real/vecN/matN/bool/int/uint/ivecN/uvecN or of a
#    struct the bodies define (locals; not by-value parameters, where it has no
#    effect) gains `precise`, so every assignment to a local, a struct member
#    of one or an array element is evaluated as written;
#  - `if (` and `while (` become `if (bc_cond = ` and `while (bc_cond = `, and
#    a `for` loop's condition `bc_cond = <condition>`: bc_cond is a global
#    `precise bool` of the prelude, so a condition's arithmetic (whose value
#    otherwise reaches no l-value) is precise too; the value tested is the
#    condition's own (assignment has the lowest precedence but the comma's);
#  - `return <value>;` becomes `{ precise <type> bc_ret = <value>; return
#    bc_ret; }` (Mesa rejects `precise` on a function's return type, and
#    glslang does not look into a return's expression), the closing part after
#    the `;` that ends the value, on whichever line (line numbers stay);
#  - out and inout parameters are precise through BC_OUT / BC_INOUT (prelude);
#  - dot( and cross( become bc_dot( and bc_cross( (prelude): GLSL's built-ins
#    may fuse their products and sums (and glslang puts no NoContraction on
#    OpDot), the prelude's spell out GLM's order, precise.
# The build then proves the coverage on the SPIR-V (check_precise.cmake).
# One line's code of blurcull_make_precise: `return <value>;` of a function
# returning <type> becomes `{ precise <type> bc_ret = <value>; return bc_ret; }`,
# the value possibly continuing on later lines (open: a value not ended yet).
function(blurcull_precise_returns code type open_var out)
  set(open ${${open_var}})
  set(result "")
  set(rest "${code}")
  while(TRUE)
    if(open)
      string(FIND "${rest}" "@S@" at)
      if(at LESS 0)
        break()
      endif()
      math(EXPR after "${at} + 3")
      string(SUBSTRING "${rest}" 0 ${at} head)
      string(SUBSTRING "${rest}" ${after} -1 rest)
      string(APPEND result "${head}@S@ return bc_ret@S@ }")
      set(open FALSE)
    else()
      string(REGEX MATCH "(^|[^A-Za-z0-9_])return[ \t]+[^@ \t]" found "${rest}")
      if(found STREQUAL "")
        break()
      endif()
      string(FIND "${rest}" "${found}" at)
      string(REGEX REPLACE "[^@ \t]$" "" found_head "${found}")
      string(LENGTH "${found_head}" found_length)
      math(EXPR after "${at} + ${found_length}")
      string(SUBSTRING "${rest}" 0 ${at} head)
      string(SUBSTRING "${rest}" ${after} -1 rest)
      string(REGEX REPLACE "return[ \t]+$" "" found_head "${found_head}")
      string(APPEND result "${head}${found_head}{ precise ${type} bc_ret = ")
      set(open TRUE)
    endif()
  endwhile()
  string(APPEND result "${rest}")
  set(${open_var} ${open} PARENT_SCOPE)
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

function(blurcull_make_precise text structs out)
  # Protect what CMake's lists would split or group on.
  string(REPLACE "@" "@A@" text "${text}")
  string(REPLACE ";" "@S@" text "${text}")
  string(REPLACE "[" "@L@" text "${text}")
  string(REPLACE "]" "@R@" text "${text}")
  string(REPLACE "\\" "@B@" text "${text}")
  set(types "real|vec2|vec3|vec4|mat2|mat3|mat4|bool|int|uint|ivec2|ivec3|ivec4|uvec2|uvec3|uvec4")
  foreach(name ${structs})
    string(APPEND types "|${name}")
  endforeach()
  string(REGEX MATCHALL "[^\n]*\n" lines "${text}")
  set(result "")
  set(in_struct FALSE)
  set(return_type void)
  set(open_return FALSE)
  set(continued FALSE)
  set(was_continued FALSE)
  foreach(line IN LISTS lines)
    if(line MATCHES "^[ \t]*#")
      string(APPEND result "${line}")
      continue()
    endif()
    string(FIND "${line}" "//" comment_at)
    if(comment_at GREATER_EQUAL 0)
      string(SUBSTRING "${line}" 0 ${comment_at} code)
      string(SUBSTRING "${line}" ${comment_at} -1 comment)
    else()
      string(REGEX REPLACE "\n$" "" code "${line}")
      set(comment "\n")
    endif()
    if(code MATCHES "^[ \t]*struct[ \t]+([A-Za-z_][A-Za-z_0-9]*)")
      set(in_struct "${CMAKE_MATCH_1}")
    elseif(in_struct)
      if(code MATCHES "^[ \t]*}")
        set(in_struct FALSE)
      endif()
    else()
      if(code MATCHES "^[ \t]*BC_FN[ \t]+([A-Za-z_][A-Za-z_0-9]*)[ \t]+[A-Za-z_]")
        set(return_type "${CMAKE_MATCH_1}")
      endif()
      if(NOT return_type STREQUAL "void")
        blurcull_precise_returns("${code}" "${return_type}" open_return code)
      endif()
      # A declaration starts a line (not one continuing a parameter list), follows
      # `{`, `;`, `for (`, BC_FN (a return type) or BC_PRECISE; parameters get
      # no `precise` (it would change nothing and draws a warning).
      set(start "[;{][ \t]*|BC_PRECISE[ \t]+|for[ \t]*\\([ \t]*")
      if(NOT continued)
        string(APPEND start "|^[ \t]*")
      endif()
      string(REGEX REPLACE "(${start})(const[ \t]+|)(${types})([ \t]+[A-Za-z_])" "\\1\\2precise \\3\\4" code "${code}")
      string(REGEX REPLACE "(^|[^A-Za-z0-9_])(if|while)[ \t]*\\(" "\\1\\2 (bc_cond = " code "${code}")
      string(REGEX REPLACE "(^|[^A-Za-z0-9_.])(dot|cross)[ \t]*\\(" "\\1bc_\\2(" code "${code}")
      string(REGEX REPLACE "(^|[^A-Za-z0-9_])for[ \t]*\\(([^@]*)@S@[ \t]*([^@ \t])" "\\1for (\\2@S@ bc_cond = \\3" code "${code}")
    endif()
    string(APPEND result "${code}${comment}")
    # The next line continues a parameter list (or a call) when this one ends in ( or ,.
    set(continued FALSE)
    if(code MATCHES "[(,][ \t]*$")
      set(continued TRUE)
    elseif(code MATCHES "^[ \t]*$")
      set(continued ${was_continued})
    endif()
    set(was_continued ${continued})
  endforeach()
  string(REPLACE "@B@" "\\" result "${result}")
  string(REPLACE "@R@" "]" result "${result}")
  string(REPLACE "@L@" "[" result "${result}")
  string(REPLACE "@S@" ";" result "${result}")
  string(REPLACE "@A@" "@" result "${result}")
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "emit")
  blurcull_read_text("${PRELUDE}" glsl)
  if(NOT glsl MATCHES "^#version ")
    message(FATAL_ERROR "EmbedGlsl: ${PRELUDE} must start with its #version line")
  endif()
  set(prelude "${glsl}")
  string(REPLACE "|" ";" body_files "${BODIES}")
  # The structs the bodies define: their variables are made precise too.
  set(structs "")
  foreach(body ${body_files})
    blurcull_read_text("${body}" text)
    string(REGEX MATCHALL "\nstruct[ \t]+[A-Za-z_][A-Za-z_0-9]*" found "${text}")
    foreach(match ${found})
      string(REGEX REPLACE "^\nstruct[ \t]+" "" match "${match}")
      list(APPEND structs ${match})
    endforeach()
  endforeach()
  set(source_string 1)
  foreach(body ${body_files})
    blurcull_read_text("${body}" text)
    blurcull_make_precise("${text}" "${structs}" text)
    get_filename_component(name "${body}" NAME)
    string(APPEND glsl "\n// ---- ${name} (source string ${source_string}) ----\n#line 1 ${source_string}\n${text}")
    math(EXPR source_string "${source_string} + 1")
  endforeach()
  blurcull_public_names("${prelude}" public_names)
  string(APPEND glsl "\n// ---- the public names: only their bc_ spelling outlives the library ----\n")
  foreach(name ${public_names})
    string(APPEND glsl "#undef ${name}\n")
  endforeach()
  blurcull_count_lines("${glsl}" lines)
  # The directive is line lines + 2 of the text; the shader's own code starts on the next.
  math(EXPR next_line "${lines} + 3")
  string(APPEND glsl "// ---- end of the blurcull kernel library ----\n#line ${next_line} 0\n")
  file(WRITE "${OUTPUT}" "${glsl}")
  blurcull_read_text("${CHECK_MAIN}" check)
  file(WRITE "${CHECK_OUTPUT}" "${glsl}${check}")
elseif(MODE STREQUAL "embed")
  file(READ "${INPUT}" hex HEX)
  string(LENGTH "${hex}" hex_length)
  math(EXPR size "${hex_length} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(REGEX REPLACE "((0x..,){20})" "\\1\n    " bytes "${bytes}")
  file(WRITE "${OUTPUT}" "// Generated by cmake/EmbedGlsl.cmake from ${INPUT}; do not edit.
#include <blurcull/glsl/kernel_glsl.hpp>

namespace blurcull::glsl {
namespace {
// Bytes rather than a string literal: the text is longer than the 65536
// characters ISO C++ promises for a literal.
constexpr char kernel_text[${size}] = {
    ${bytes}};
}  // namespace

std::string_view kernel_source() { return std::string_view(kernel_text, sizeof kernel_text); }

std::string_view kernel_source_without_version() {
    std::string_view text = kernel_source();
    return text.substr(text.find('\\n') + 1);
}

}  // namespace blurcull::glsl
")
else()
  message(FATAL_ERROR "EmbedGlsl: MODE must be emit or embed, not '${MODE}'")
endif()
