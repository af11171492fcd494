# Functions longer than a limit outside tests, by a brace count of each `fn` body (braces in
# strings are counted too, so a body with many is over-counted): `python3 tests/tools/long_functions.py src 80`.
import re,os,sys
root=sys.argv[1]; limit=int(sys.argv[2]) if len(sys.argv)>2 else 80
out=[]
for d,_,fs in os.walk(root):
    for f in fs:
        if not f.endswith('.rs') or f.endswith('tests.rs') or f=='tests.rs': continue
        p=os.path.join(d,f); lines=open(p).read().split('\n')
        # cut test modules
        end=len(lines)
        for i,l in enumerate(lines):
            if l.startswith('#[cfg(test)]') and i+1<len(lines) and 'mod tests' in lines[i+1]:
                end=i;break
        i=0
        while i<end:
            m=re.match(r'\s*(pub(\([^)]*\))? )?(const )?(async )?fn (\w+)',lines[i])
            if m and not lines[i].rstrip().endswith(';'):
                depth=0;started=False;j=i
                while j<end:
                    depth+=lines[j].count('{')-lines[j].count('}')
                    if '{' in lines[j]: started=True
                    if started and depth<=0: break
                    j+=1
                n=j-i+1
                if n>limit: out.append((n,p,m.group(5)))
                i=j+1 if started else i+1
            else: i+=1
out.sort(reverse=True)
print(len(out))
for o in out[:int(sys.argv[3]) if len(sys.argv)>3 else 10]: print(o)
