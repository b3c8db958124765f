#!/usr/bin/env bash
# DocsCommandLineReference: docs/reference/command-line.md must be exactly what the program
# prints with `cbrbench help --markdown` (built from the CLI11 option definitions).
# Usage: check_cli_reference.sh CBRBENCH DOC_MD
set -euo pipefail
exe=$1 doc=$2
if ! diff -u "$doc" <("$exe" help --markdown); then
  echo "check_cli_reference: $doc differs from \`cbrbench help --markdown\` (above: - the file, + the program)."
  echo "Regenerate it: build/harness/cbrbench help --markdown > docs/reference/command-line.md"
  exit 1
fi
echo "check_cli_reference: $doc matches the program's options"
