# shellcheck shell=bash
# The command line the bash scripts in scripts/ share; they source it (it runs nothing by itself).
#   cli_help "$@"                 -h or --help among the arguments: prints the calling script's header comment
#                                 (its usage, from its second line to the first line that is not a comment)
#                                 and exits 0, before anything else runs
#   cli_refuse_options ARG ...    an argument that looks like an option (-x, --x) is refused:
#                                 "SCRIPT: unknown option 'ARG'; see --help" on stderr, exit 2
#   cli_fail MESSAGE              "SCRIPT: MESSAGE; see --help" on stderr, exit 2
#   cli_is_positive NUMBER        true when NUMBER is a decimal number > 0 (digits with at most one point)
# SCRIPT is the calling script's file name.

cli_help() {
  local arg
  for arg in "$@"; do
    case "$arg" in -h | --help)
      sed -n -e '1d' -e '/^#/!q' -e 's/^# \{0,1\}//p' "${BASH_SOURCE[1]}"
      exit 0
      ;;
    esac
  done
}

cli_fail() {
  echo "$(basename "${BASH_SOURCE[1]}"): $1; see --help" >&2
  exit 2
}

cli_refuse_options() {
  local arg
  for arg in "$@"; do
    case "$arg" in -?*) echo "$(basename "${BASH_SOURCE[1]}"): unknown option '$arg'; see --help" >&2; exit 2 ;; esac
  done
}

cli_is_positive() {
  [[ "$1" =~ ^[0-9]*\.?[0-9]+$ && "$1" =~ [1-9] ]]
}
