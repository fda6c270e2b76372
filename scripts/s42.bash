# bash completion for s42 (installed by `make install` into
# share/bash-completion/completions/s42).  The options of each command are
# read from `s42 COMMAND --help`, so this file never lists them twice.
_s42()
{
  local cur prev cmd words
  cur=${COMP_WORDS[COMP_CWORD]}
  prev=${COMP_WORDS[COMP_CWORD-1]}
  cmd=${COMP_WORDS[1]}
  if [ "$COMP_CWORD" -eq 1 ]; then
    COMPREPLY=($(compgen -W "run tui check disasm plot plugins dialects help --help --version" -- "$cur"))
    return
  fi
  case $prev in
    --operator|--tool|--tools|--state|-o)
      COMPREPLY=($(compgen -f -- "$cur")); return ;;
    --plugins|--dump-images)
      COMPREPLY=($(compgen -d -- "$cur")); return ;;
    --lang)
      COMPREPLY=($(compgen -W "uk en" -- "$cur")); return ;;
    --dialect)
      COMPREPLY=($(compgen -W "$("${COMP_WORDS[0]}" dialects 2>/dev/null | awk 'NR>1{print $1}')" -- "$cur")); return ;;
    --max-blocks|--modbus-max-clients|--modbus-idle|--modbus-allow|--stock)
      return ;;
  esac
  if [ "$cmd" = help ]; then
    COMPREPLY=($(compgen -W "run tui check disasm plot plugins" -- "$cur"))
    return
  fi
  if [[ $cur == -* ]]; then
    words=$("${COMP_WORDS[0]}" "$cmd" --help 2>/dev/null | sed -n 's/^  \(-[^ []*\).*/\1/p')
    COMPREPLY=($(compgen -W "$words --help" -- "$cur"))
    return
  fi
  # program files: .kp first, directories to walk into
  COMPREPLY=($(compgen -f -X '!*.kp' -- "$cur") $(compgen -d -- "$cur"))
}
complete -o filenames -F _s42 s42
