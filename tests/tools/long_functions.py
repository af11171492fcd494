# Functions longer than a limit outside tests, by counting the braces of each `fn` body with
# string and character literals and comments left out:
#   python3 tests/tools/long_functions.py src 80 [how many to list]
import os
import re
import sys

LITERAL = re.compile(
    r'r(#*)"(?:.|\n)*?"\1'          # raw strings
    r'|"(?:\\[\s\S]|[^"\\])*"'      # strings, a line's end escaped in them
    r"|'(?:\\.|[^'\\])'"            # characters (not lifetimes)
    r'|//[^\n]*'                    # comments
)


def blank(text):
    """The text with every literal and comment replaced by spaces, newlines kept."""
    return LITERAL.sub(lambda m: re.sub(r'[^\n]', ' ', m.group(0)), text)


def long_functions(root, limit):
    out = []
    for d, _, files in os.walk(root):
        for f in files:
            if not f.endswith('.rs') or f.endswith('tests.rs'):
                continue
            path = os.path.join(d, f)
            lines = blank(open(path).read()).split('\n')
            end = len(lines)
            for i, line in enumerate(lines):
                if line.startswith('#[cfg(test)]') and i + 1 < end and 'mod tests' in lines[i + 1]:
                    end = i
                    break
            i = 0
            while i < end:
                m = re.match(r'\s*(pub(\([^)]*\))? )?(const )?(async )?fn (\w+)', lines[i])
                if not m:
                    i += 1
                    continue
                depth, started, j = 0, False, i
                while j < end:
                    if ';' in lines[j] and not started and '{' not in lines[j]:
                        break
                    depth += lines[j].count('{') - lines[j].count('}')
                    started = started or '{' in lines[j]
                    if started and depth <= 0:
                        break
                    j += 1
                if started and j - i + 1 > limit:
                    out.append((j - i + 1, path, m.group(5)))
                i = j + 1
    return sorted(out, reverse=True)


if __name__ == '__main__':
    found = long_functions(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 80)
    print(len(found))
    for row in found[: int(sys.argv[3]) if len(sys.argv) > 3 else 10]:
        print(row)
