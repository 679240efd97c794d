"""Print the commands of the README's Quick start, one per line, exactly as written."""

import re
import sys
from pathlib import Path

text = Path(sys.argv[1] if len(sys.argv) > 1 else "README.md").read_text()
section = re.search(r"^## Quick start\n(.*?)(?=^## )", text, re.S | re.M)
if not section:
    sys.exit("README.md has no '## Quick start' section")
blocks = re.findall(r"```bash\n(.*?)```", section.group(1), re.S)
if len(blocks) != 1:
    sys.exit(f"the Quick start must hold exactly one bash block, found {len(blocks)}")
commands = [line for line in blocks[0].splitlines() if line.strip() and not line.lstrip().startswith("#")]
if len(commands) != 2:
    sys.exit(f"the Quick start must hold exactly two commands, found {len(commands)}")
print("\n".join(commands))
