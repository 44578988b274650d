import tomllib,sys
m=tomllib.load(open(sys.argv[1],'rb'))
print('peak_rss', m['run'].get('peak_rss_mb'), 'assembly_s', m['run'].get('assembly_seconds'))
for s in m['linear_solve']:
    print(s.get('step'),s.get('newton_iteration'),s.get('krylov_iterations'),round(s['memory_heap_MB']),round(s['memory_heap_free_MB']),round(s['memory_resident_MB']),round(s['memory_peak_resident_MB']))
